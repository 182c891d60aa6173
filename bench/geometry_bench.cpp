// geometry_bench.cpp — shadow-volume geometry on closed meshes (UV spheres) from 10k to 4M
// triangles: adjacency (ours against meshoptimizer's meshopt_generateAdjacencyIndexBuffer, the
// same index buffer out), silhouette extraction, and the whole per-light work (silhouette + the
// infinite volume with both caps, and with sides only: the z-pass case), and the streaming floor
// of that per-light work (BM_VolumePerLight_Floor, BM_VolumePerLight_SidesOnly_Floor: the bytes it
// must move, below). Targets: under 10 ms per light at 1M triangles on one core; adjacency at
// least 4x meshoptimizer at 1M and 4M triangles, 1x at 10k; the per-light passes within 1.5x of
// their floor at 100k, 1M and 4M.
#include <benchmark/benchmark.h>
#include <emmintrin.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "bench_support.hpp"
#include "shadowref/adjacency.hpp"
#include "shadowref/primitives.hpp"
#include "shadowref/silhouette.hpp"
#include "shadowref/volume.hpp"

namespace {

using Caster = shadowref::ShadowCaster<float>;

// A UV sphere with about `triangles` triangles: s segments, s/2 + 1 rings, s² triangles.
shadowref::TriangleMesh<float> sphere(std::int64_t triangles) {
  auto s = static_cast<std::uint32_t>(std::lround(std::sqrt(static_cast<double>(triangles))));
  s += s % 2;
  return shadowref::make_uv_sphere(1.0f, s, s / 2 + 1).value();
}

const Caster& caster(std::int64_t triangles) {
  static std::map<std::int64_t, Caster> cache;
  auto it = cache.find(triangles);
  if (it == cache.end()) it = cache.emplace(triangles, shadowref::make_shadow_caster(sphere(triangles)).value()).first;
  return it->second;
}

const shadowref::Vec4<float> kLight(3.0f, 4.0f, 2.0f, 1.0f);

void finish(benchmark::State& state, std::size_t triangles) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(triangles));
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["edges_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * 1.5 * static_cast<double>(triangles),
                                                     benchmark::Counter::kIsRate);
  shadowref::bench::report_peak_rss(state);
}

void BM_Adjacency_Ours(benchmark::State& state) {
  const auto mesh = sphere(state.range(0));
  std::vector<std::uint32_t> out;
  for (auto _ : state) {
    const auto adj = shadowref::build_adjacency(mesh).value();
    shadowref::adjacency_index_buffer(mesh, adj, out);
    benchmark::DoNotOptimize(out.data());
  }
  finish(state, mesh.triangles.size());
}

void BM_Adjacency_Meshopt(benchmark::State& state) {
  const auto mesh = sphere(state.range(0));
  static_assert(sizeof(mesh.positions[0]) == 3 * sizeof(float) && sizeof(mesh.triangles[0]) == 3 * sizeof(unsigned));
  std::vector<unsigned> out(6 * mesh.triangles.size());
  for (auto _ : state) {
    meshopt_generateAdjacencyIndexBuffer(out.data(), mesh.triangles[0].data(), 3 * mesh.triangles.size(),
                                         mesh.positions[0].data(), mesh.positions.size(), 3 * sizeof(float));
    benchmark::DoNotOptimize(out.data());
  }
  finish(state, mesh.triangles.size());
}

void BM_Silhouette(benchmark::State& state) {
  const Caster& c = caster(state.range(0));
  shadowref::Silhouette<float> sil;
  for (auto _ : state) {
    auto n = shadowref::find_silhouette(c, kLight, sil);
    benchmark::DoNotOptimize(n);
  }
  finish(state, c.mesh.triangles.size());
  state.counters["silhouette_edges"] = static_cast<double>(sil.edges.size());
}

// Everything a light costs once the caster is prepared: silhouette, sides and both caps. One light
// before the timed loop: the output buffers grow (allocation, first touch) once per caster and are
// reused from light to light (volume.hpp), which is the cost measured here; at 4M triangles that
// first light costs about 4x a later one, and in a short run it was a quarter of the mean.
void BM_VolumePerLight(benchmark::State& state) {
  const Caster& c = caster(state.range(0));
  shadowref::Silhouette<float> sil;
  shadowref::ShadowVolume<float> vol;
  (void)shadowref::find_silhouette(c, kLight, sil).value();
  (void)shadowref::build_shadow_volume(c, sil, shadowref::VolumeOptions<float>{}, vol).value();
  for (auto _ : state) {
    auto n = shadowref::find_silhouette(c, kLight, sil);
    auto r = shadowref::build_shadow_volume(c, sil, shadowref::VolumeOptions<float>{}, vol);
    benchmark::DoNotOptimize(n);
    benchmark::DoNotOptimize(r);
  }
  finish(state, c.mesh.triangles.size());
  state.counters["volume_triangles"] = static_cast<double>(vol.ranges.triangle_count());
}

// The z-pass case: silhouette and side quads only (no caps).
void BM_VolumePerLight_SidesOnly(benchmark::State& state) {
  const Caster& c = caster(state.range(0));
  shadowref::Silhouette<float> sil;
  shadowref::ShadowVolume<float> vol;
  shadowref::VolumeOptions<float> sides_only;
  sides_only.light_cap = sides_only.dark_cap = false;
  (void)shadowref::find_silhouette(c, kLight, sil).value();  // the buffers grown first, as above
  (void)shadowref::build_shadow_volume(c, sil, sides_only, vol).value();
  for (auto _ : state) {
    auto n = shadowref::find_silhouette(c, kLight, sil);
    auto r = shadowref::build_shadow_volume(c, sil, sides_only, vol);
    benchmark::DoNotOptimize(n);
    benchmark::DoNotOptimize(r);
  }
  finish(state, c.mesh.triangles.size());
  state.counters["volume_triangles"] = static_cast<double>(vol.ranges.triangle_count());
}

// The streaming floor of a per-light pass: the bytes BM_VolumePerLight (capped) or
// BM_VolumePerLight_SidesOnly must read and write for this sphere and light, counted from the real
// structures after one real pass, streamed with plain loops (reads XOR-folded 32-bit words, writes
// stores of 32-bit words, 64 bytes an iteration: xor_fold, fill_words), every buffer allocated and
// touched before the timed loop. It streams:
//   read   the caster's face planes: 4 arrays of T floats (16 B per triangle; classify_faces);
//   read   the caster's edge_block_faces tables (the skip test of every block of edges), and the
//          edge_use_pairs of the blocks the pass does not skip: 2 uint32 per edge (8 B per edge),
//          the blocks found with silhouette.hpp's own rule from this light's lit flags;
//   read   the lit faces' triangles: 12 B per lit face (the caps name them; capped only);
//   read   the used vertices' positions: 12 B per volume vertex source (the vertex buffer's input);
//   write  the lit flags: 1 B per triangle (Silhouette::lit, an output of find_silhouette);
//   write  the silhouette edges: 8 B each;
//   write  the volume: 4 B per index, 16 B per vertex (Vec4<float>), 4 B per source entry.
// These are the bytes the pass itself reads and writes, so the pass cannot beat its floor (an
// earlier floor streamed every edge pair while the pass skips the blocks far from the
// silhouette, and the sides-only pass came out at 0.9x of it). Not counted: what the algorithm
// re-reads (the lit flags, for the skip test, the edge test and the caps), the volume_vertex
// numbering, the named edges' triangles. The lit faces' triangles and the used positions are
// streamed as that many contiguous bytes from the start of the arrays (the real ones are
// scattered: a floor). The ratio ours / floor is what geometry goal B tracks.
struct FloorSpans {
  std::vector<std::pair<const std::uint32_t*, std::size_t>> reads;  // (words, count)
  std::vector<std::vector<std::uint32_t>> writes;                   // one buffer per output, touched
  std::size_t bytes = 0;
  std::size_t pair_words = 0;          // of edge_use_pairs, read by the pass
  double visited_pair_fraction = 0;    // their share of all the pairs
};

FloorSpans floor_spans(const Caster& c, const shadowref::VolumeOptions<float>& options) {
  shadowref::Silhouette<float> sil;
  shadowref::ShadowVolume<float> vol;
  (void)shadowref::find_silhouette(c, kLight, sil).value();
  (void)shadowref::build_shadow_volume(c, sil, options, vol).value();
  const bool caps = options.light_cap || options.dark_cap;
  const std::size_t nt = c.mesh.triangles.size();
  FloorSpans f;
  const auto words = [](const float* p) { return reinterpret_cast<const std::uint32_t*>(p); };
  const auto read = [&](const std::uint32_t* p, std::size_t n) {
    f.reads.emplace_back(p, n), f.bytes += 4 * n;
    if (p >= c.edge_use_pairs.data() && p < c.edge_use_pairs.data() + c.edge_use_pairs.size()) f.pair_words += n;
  };
  const auto write = [&](std::size_t bytes) { f.writes.emplace_back((bytes + 3) / 4, 1u), f.bytes += 4 * ((bytes + 3) / 4); };
  for (const auto* plane : {&c.face_planes.x, &c.face_planes.y, &c.face_planes.z, &c.face_planes.w}) read(words(plane->data()), nt);
  read(c.edge_block_face_offsets.data(), c.edge_block_face_offsets.size());
  read(c.edge_block_faces.data(), c.edge_block_faces.size());
  // The blocks find_silhouette reads the pairs of: those whose faces are not all lit or all unlit.
  const std::size_t ne = c.adjacency.edge_count(), block = shadowref::kSilhouetteEdgeBlock;
  for (std::size_t base = 0; base < ne; base += block) {
    const std::size_t k = base / block;
    bool skipped = false;
    if (c.edge_block_face_offsets[k] != c.edge_block_face_offsets[k + 1]) {
      const std::uint8_t first = sil.lit[c.edge_block_faces[2 * c.edge_block_face_offsets[k]]];
      skipped = true;
      for (std::uint32_t r = c.edge_block_face_offsets[k]; r < c.edge_block_face_offsets[k + 1] && skipped; ++r)
        for (std::uint32_t t = c.edge_block_faces[2 * r]; t < c.edge_block_faces[2 * r + 1]; ++t)
          if (sil.lit[t] != first) skipped = false;
    }
    if (!skipped) read(c.edge_use_pairs.data() + 2 * base, 2 * (std::min(ne, base + block) - base));
  }
  f.visited_pair_fraction = static_cast<double>(f.pair_words) / static_cast<double>(c.edge_use_pairs.size());
  if (caps) read(c.mesh.triangles[0].data(), 3 * sil.lit_count);
  read(words(c.mesh.positions[0].data()), 3 * vol.source.size());
  write(nt);
  write(sizeof(shadowref::SilhouetteEdge) * sil.edges.size());
  write(sizeof(std::uint32_t) * vol.indices.size());
  write(sizeof(shadowref::Vec4<float>) * vol.vertices.size());
  write(sizeof(std::uint32_t) * vol.source.size());
  return f;
}

// The floor's own loops, 64 bytes an iteration with four independent accumulators (SSE2): a loop of
// one 16-byte load and one xor ran at one iteration a cycle, so it measured the front end, not
// memory — moving it across a 64-byte code boundary (an unrelated change elsewhere in the binary)
// made the same floor 1.7x slower (0.38 -> 0.65 ms, sides only at 1M triangles).
std::uint32_t xor_fold(const std::uint32_t* p, std::size_t n) {
  __m128i a = _mm_setzero_si128(), b = a, c = a, d = a;
  std::size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    a = _mm_xor_si128(a, _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i)));
    b = _mm_xor_si128(b, _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i + 4)));
    c = _mm_xor_si128(c, _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i + 8)));
    d = _mm_xor_si128(d, _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i + 12)));
  }
  alignas(16) std::uint32_t lanes[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(lanes), _mm_xor_si128(_mm_xor_si128(a, b), _mm_xor_si128(c, d)));
  std::uint32_t fold = lanes[0] ^ lanes[1] ^ lanes[2] ^ lanes[3];
  for (; i < n; ++i) fold ^= p[i];
  return fold;
}

void fill_words(std::uint32_t* d, std::size_t n, std::uint32_t value) {
  const __m128i v = _mm_set1_epi32(static_cast<int>(value));
  std::size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(d + i), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(d + i + 4), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(d + i + 8), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(d + i + 12), v);
  }
  for (; i < n; ++i) d[i] = value;
}

void run_floor(benchmark::State& state, const shadowref::VolumeOptions<float>& options) {
  const Caster& c = caster(state.range(0));
  FloorSpans f = floor_spans(c, options);
  for (auto _ : state) {
    std::uint32_t fold = 0;
    for (const auto& [p, n] : f.reads) fold ^= xor_fold(p, n);
    benchmark::DoNotOptimize(fold);
    for (auto& w : f.writes) fill_words(w.data(), w.size(), fold);
    benchmark::ClobberMemory();
  }
  finish(state, c.mesh.triangles.size());
  state.counters["floor_MB"] = static_cast<double>(f.bytes) / 1e6;
  state.counters["pairs_read"] = f.visited_pair_fraction;
  state.counters["floor_bytes_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(f.bytes),
                                                          benchmark::Counter::kIsRate);
}

void BM_VolumePerLight_Floor(benchmark::State& state) { run_floor(state, shadowref::VolumeOptions<float>{}); }

void BM_VolumePerLight_SidesOnly_Floor(benchmark::State& state) {
  shadowref::VolumeOptions<float> sides_only;
  sides_only.light_cap = sides_only.dark_cap = false;
  run_floor(state, sides_only);
}

void mesh_sizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {10000, 100000, 1000000, 4000000}) b->Arg(n);
  b->ArgName("tris")->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
}
BENCHMARK(BM_Adjacency_Ours)->Apply(mesh_sizes);
BENCHMARK(BM_Adjacency_Meshopt)->Apply(mesh_sizes);
BENCHMARK(BM_Silhouette)->Apply(mesh_sizes);
BENCHMARK(BM_VolumePerLight)->Apply(mesh_sizes);
BENCHMARK(BM_VolumePerLight_SidesOnly)->Apply(mesh_sizes);
BENCHMARK(BM_VolumePerLight_Floor)->Apply(mesh_sizes);
BENCHMARK(BM_VolumePerLight_SidesOnly_Floor)->Apply(mesh_sizes);

}  // namespace

BENCHMARK_MAIN();
