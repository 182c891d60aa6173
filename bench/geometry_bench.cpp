// geometry_bench.cpp — shadow-volume geometry on closed meshes (UV spheres) from 10k to 4M
// triangles: adjacency (ours against meshoptimizer's meshopt_generateAdjacencyIndexBuffer, the
// same index buffer out), silhouette extraction, and the whole per-light work (silhouette + the
// infinite volume with both caps, and with sides only: the z-pass case). Target: under 10 ms per
// light at 1M triangles on one core.
#include <benchmark/benchmark.h>
#include <meshoptimizer.h>

#include <cmath>
#include <map>
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

// Everything a light costs once the caster is prepared: silhouette, sides and both caps.
void BM_VolumePerLight(benchmark::State& state) {
  const Caster& c = caster(state.range(0));
  shadowref::Silhouette<float> sil;
  shadowref::ShadowVolume<float> vol;
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
  for (auto _ : state) {
    auto n = shadowref::find_silhouette(c, kLight, sil);
    auto r = shadowref::build_shadow_volume(c, sil, sides_only, vol);
    benchmark::DoNotOptimize(n);
    benchmark::DoNotOptimize(r);
  }
  finish(state, c.mesh.triangles.size());
  state.counters["volume_triangles"] = static_cast<double>(vol.ranges.triangle_count());
}

void mesh_sizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {10000, 100000, 1000000, 4000000}) b->Arg(n);
  b->ArgName("tris")->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_Adjacency_Ours)->Apply(mesh_sizes);
BENCHMARK(BM_Adjacency_Meshopt)->Apply(mesh_sizes);
BENCHMARK(BM_Silhouette)->Apply(mesh_sizes);
BENCHMARK(BM_VolumePerLight)->Apply(mesh_sizes);
BENCHMARK(BM_VolumePerLight_SidesOnly)->Apply(mesh_sizes);

}  // namespace

BENCHMARK_MAIN();
