// reference_bench.cpp — the reference's shadow rays against a bare Embree loop over the same rays,
// in the same run, on one thread and on all threads; the BVH build; a whole reference render.
//
//   BM_ShadowRays_Ours    the reference's own shadow-ray stage, the functions render()'s tiles call
//                         (shadow_ray.hpp): from surface points and normals (rounded to float,
//                         structure of arrays) to lit answers — build_shadow_rays over 4096 queries
//                         at a time into a RayStream reused per thread (attached ones left inactive
//                         in it), then occlude_shadow_rays (rtcOccludedNp under flush-to-zero, one lit
//                         byte per query). Not render() itself: its tiles interleave primary rays,
//                         surfaces and the gather (BM_ReferenceRender times all of it).
//   BM_ShadowRays_Bare    rtcOccluded1M over the very rays Ours traces, already built (only tfar,
//                         which Embree overwrites on a hit, is restored before each call): the
//                         ceiling. Goal: Bare time / Ours time >= 0.95. Both sides pinned alike:
//                         the same API (rtcOccluded1M, 4096-ray chunks), the same context flags
//                         (COHERENT), the same TBB arena of 1 or 2 threads, the same 16384-query tasks.
//   BM_ShadowRays_BareNp  rtcOccludedNp over the same rays as Bare, already built in a structure of
//                         arrays (tfar restored before each call): the ceiling of the API Ours calls
//                         (Embree's SoA stream path skips the transposition its AoS one does).
//   BM_ShadowRays_Build   Ours without occlude_shadow_rays: where the gap between the two goes
//                         (build_shadow_rays, in float, vectorised: a square root and a division per ray).
//   BM_ReferenceRender    a whole reference render; its counter ray_work_over_embree is the tiles'
//                         whole ray work (primary rays, surfaces, shadow rays with the decided
//                         test's nudges) over the time inside Embree's calls on those very rays
//                         (reference::Stats; occlude_shadow_rays' read-back of the answers, a byte a
//                         ray, counts as Embree's). Goal: <= 1.3.
// The surface points are the pixel-centre hits of the scene's camera at 1024 × 1024, the light its
// first light's homogeneous point, the offset the scene's epsilon: the pixel-centre rays a render
// traces. The bare loops trace under the reference's own FlushDenormalsGuard (flush_denormals.hpp).
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <Eigen/LU>
#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/reference/flush_denormals.hpp"
#include "shadowref/reference/ray_stream.hpp"
#include "shadowref/reference/render.hpp"
#include "shadowref/reference/shadow_ray.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace {

using shadowref::Vec3;
using shadowref::Vec4;
namespace ref = shadowref::reference;
namespace sc = shadowref::scene;

constexpr int kResolution = 1024;
constexpr std::size_t kBlock = 16384;  // queries per parallel task (both paths split alike)
constexpr std::size_t kChunk = 4096;   // rays per rtcOccluded1M call, as in render.cpp

using Ftz = ref::FlushDenormalsGuard;  // for the bare loops: the mode the reference traces in

struct Case {
  sc::Scene scene;
  std::unique_ptr<ref::EmbreeScene> embree;
  std::vector<Vec3<double>> p, n;   // pixel-centre hits
  std::vector<float> px, py, pz, nx, ny, nz;  // the same rounded to float, as render() hands them on
  Vec4<double> light;
  double offset = 0;
  std::vector<RTCRay> rays;         // the traced rays (make_shadow_ray's Trace kind), in query order
  std::vector<float> tfar;          // their tfar before tracing
  ref::RayStream soa;               // the same rays as a structure of arrays (BareNp)
};

Case& get_case(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Case>> cache;
  auto& slot = cache[name];
  if (slot) return *slot;
  slot = std::make_unique<Case>();
  Case& c = *slot;
  c.scene = sc::load_scene(std::string(SHADOWREF_SCENES_DIR) + "/" + name + ".json");
  c.scene.width = c.scene.height = kResolution;
  Ftz ftz;
  c.embree = std::make_unique<ref::EmbreeScene>(c.scene);
  const auto inv = (sc::projection_matrix<double>(c.scene.camera, kResolution, kResolution).value() *
                    sc::view_matrix<double>(c.scene.camera).value()).inverse().eval();
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (int y = 0; y < kResolution; ++y)
    for (int x = 0; x < kResolution; ++x) {
      const auto ndc = sc::pixel_to_ndc<double>(x, y, 0.5, 0.5, kResolution, kResolution);
      auto unproject = [&](double z) {
        const Vec4<double> h = inv * Vec4<double>(ndc.x(), ndc.y(), z, 1.0);
        return Vec3<double>(h.head<3>() / h[3]);
      };
      const Vec3<double> o = unproject(-1.0), d = (unproject(0.0) - o).normalized();
      RTCRayHit rh{};
      rh.ray.org_x = static_cast<float>(o.x()), rh.ray.org_y = static_cast<float>(o.y()), rh.ray.org_z = static_cast<float>(o.z());
      rh.ray.dir_x = static_cast<float>(d.x()), rh.ray.dir_y = static_cast<float>(d.y()), rh.ray.dir_z = static_cast<float>(d.z());
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.mask = 0xFFFFFFFFu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(c.embree->handle(), &ctx, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      Vec3<double> ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
      if (!(ng.norm() > 0)) continue;
      ng.normalize();
      c.p.push_back(o + static_cast<double>(rh.ray.tfar) * d);
      c.n.push_back(ng.dot(d) > 0 ? Vec3<double>(-ng) : ng);
    }
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    c.px.push_back(static_cast<float>(c.p[i].x())), c.py.push_back(static_cast<float>(c.p[i].y()));
    c.pz.push_back(static_cast<float>(c.p[i].z()));
    c.nx.push_back(static_cast<float>(c.n[i].x())), c.ny.push_back(static_cast<float>(c.n[i].y()));
    c.nz.push_back(static_cast<float>(c.n[i].z()));
  }
  c.light = sc::homogeneous(c.scene.lights.front());
  c.offset = c.embree->epsilon();
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    RTCRay ray{};
    if (ref::make_shadow_ray(c.p[i], c.n[i], c.light, c.offset, ray) != ref::ShadowRayKind::Trace) continue;
    c.rays.push_back(ray);
    c.tfar.push_back(ray.tfar);
  }
  c.soa.resize(c.rays.size());
  for (std::size_t i = 0; i < c.rays.size(); ++i) {
    const RTCRay& r = c.rays[i];
    c.soa.org_x[i] = r.org_x, c.soa.org_y[i] = r.org_y, c.soa.org_z[i] = r.org_z, c.soa.tnear[i] = r.tnear;
    c.soa.dir_x[i] = r.dir_x, c.soa.dir_y[i] = r.dir_y, c.soa.dir_z[i] = r.dir_z, c.soa.tfar[i] = r.tfar;
  }
  return c;
}

int arena_threads(benchmark::State& state) {
  return state.range(0) > 0 ? static_cast<int>(state.range(0)) : tbb::task_arena::automatic;
}

void finish(benchmark::State& state, const Case& c) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(c.rays.size()));
  state.counters["rays"] = static_cast<double>(c.rays.size());
  state.counters["triangles"] = static_cast<double>(c.embree ? [&] {
    std::size_t t = 0;
    for (const auto& o : c.scene.objects) t += o.mesh.triangles.size();
    return t;
  }() : 0);
  state.counters["threads"] = static_cast<double>(tbb::task_arena(arena_threads(state)).max_concurrency());
  shadowref::bench::report_peak_rss(state);
}

void BM_ShadowRays_Bare(benchmark::State& state, const std::string& name) {
  Case& c = get_case(name);
  tbb::task_arena arena(arena_threads(state));
  const std::size_t blocks = (c.rays.size() + kBlock - 1) / kBlock;
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        Ftz ftz;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        for (std::size_t b = r.begin(); b < r.end(); ++b) {
          const std::size_t end = std::min(c.rays.size(), (b + 1) * kBlock);
          for (std::size_t first = b * kBlock; first < end; first += kChunk) {
            const std::size_t count = std::min(kChunk, end - first);
            for (std::size_t i = first; i < first + count; ++i) c.rays[i].tfar = c.tfar[i];
            rtcOccluded1M(c.embree->handle(), &ctx, c.rays.data() + first, static_cast<unsigned>(count), sizeof(RTCRay));
          }
          benchmark::DoNotOptimize(c.rays[b * kBlock].tfar);
        }
      });
    });
  }
  finish(state, c);
}

void BM_ShadowRays_BareNp(benchmark::State& state, const std::string& name) {
  Case& c = get_case(name);
  tbb::task_arena arena(arena_threads(state));
  const std::size_t blocks = (c.rays.size() + kBlock - 1) / kBlock;
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        Ftz ftz;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        RTCRayNp all = c.soa.rays();
        for (std::size_t b = r.begin(); b < r.end(); ++b) {
          const std::size_t end = std::min(c.rays.size(), (b + 1) * kBlock);
          for (std::size_t first = b * kBlock; first < end; first += kChunk) {
            const std::size_t count = std::min(kChunk, end - first);
            for (std::size_t i = first; i < first + count; ++i) c.soa.tfar[i] = c.tfar[i];
            RTCRayNp np = all;
            for (float** f : {&np.org_x, &np.org_y, &np.org_z, &np.tnear, &np.dir_x, &np.dir_y, &np.dir_z, &np.time, &np.tfar})
              *f += first;
            for (unsigned** u : {&np.mask, &np.id, &np.flags}) *u += first;
            rtcOccludedNp(c.embree->handle(), &ctx, &np, static_cast<unsigned>(count));
          }
          benchmark::DoNotOptimize(c.soa.tfar[b * kBlock]);
        }
      });
    });
  }
  finish(state, c);
}

// Ours, or (trace = false) only the building of its rays: one loop, so that the two differ in the
// tracing alone.
void shadow_rays(benchmark::State& state, const std::string& name, bool trace) {
  Case& c = get_case(name);
  tbb::task_arena arena(arena_threads(state));
  struct Scratch {
    ref::RayStream rays;
    std::vector<std::uint8_t> lit;
  };
  tbb::enumerable_thread_specific<Scratch> buffers;
  const std::size_t blocks = (c.p.size() + kBlock - 1) / kBlock;
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        Scratch& s = buffers.local();
        s.lit.resize(kBlock);
        for (std::size_t b = r.begin(); b < r.end(); ++b) {
          const std::size_t end = std::min(c.p.size(), (b + 1) * kBlock);
          for (std::size_t first = b * kBlock; first < end; first += kChunk) {
            const std::size_t count = std::min(kChunk, end - first);
            s.rays.resize(count);
            const ref::SurfacePoints points{c.px.data() + first, c.py.data() + first, c.pz.data() + first,
                                            c.nx.data() + first, c.ny.data() + first, c.nz.data() + first};
            ref::build_shadow_rays(points, count, c.light, c.offset, s.rays, 0);
            if (!trace) {
              benchmark::DoNotOptimize(s.rays.tfar);
              benchmark::ClobberMemory();
              continue;
            }
            ref::occlude_shadow_rays(*c.embree, s.rays, count, s.lit.data() + (first - b * kBlock));
          }
          benchmark::DoNotOptimize(s.lit.data());
        }
      });
    });
  }
  finish(state, c);
}

void BM_ShadowRays_Ours(benchmark::State& state, const std::string& name) { shadow_rays(state, name, true); }
void BM_ShadowRays_Build(benchmark::State& state, const std::string& name) { shadow_rays(state, name, false); }

void BM_SceneBuild(benchmark::State& state, const std::string& name) {
  Case& c = get_case(name);
  tbb::task_arena arena(arena_threads(state));
  for (auto _ : state) {
    arena.execute([&] {
      Ftz ftz;
      ref::EmbreeScene e(c.scene);
      benchmark::DoNotOptimize(e.handle());
    });
  }
  finish(state, c);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(state.counters["triangles"].value));
}

// A whole reference render at the scene's own resolution (4 × 4 sub-pixel samples); embree_share
// is the shadow phase's time inside Embree (Stats), for context: the phase also shades.
void BM_ReferenceRender(benchmark::State& state, const std::string& name) {
  const sc::Scene scene = sc::load_scene(std::string(SHADOWREF_SCENES_DIR) + "/" + name + ".json");
  ref::Options options;
  options.threads = static_cast<int>(state.range(0));
  ref::Stats stats;
  for (auto _ : state) {
    auto images = ref::render(scene, options, &stats);
    benchmark::DoNotOptimize(images.decided.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * scene.width * scene.height);
  state.counters["pixels_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * scene.width * scene.height,
                                                      benchmark::Counter::kIsRate);
  state.counters["embree_share"] = stats.seconds_shadow_calls / stats.seconds_shadow_phase;
  state.counters["ray_work_over_embree"] = stats.seconds_ray_work / (stats.seconds_primary_calls + stats.seconds_shadow_calls);
  shadowref::bench::report_peak_rss(state);
}

// 1 and 2 threads, pinned (an arena of exactly that many), so that a run means the same on a bigger machine.
void threads(benchmark::internal::Benchmark* b) {
  b->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
}

#define SHADOW_RAY_CASES(scene)                                           \
  BENCHMARK_CAPTURE(BM_ShadowRays_Ours, scene, #scene)->Apply(threads);   \
  BENCHMARK_CAPTURE(BM_ShadowRays_Bare, scene, #scene)->Apply(threads);   \
  BENCHMARK_CAPTURE(BM_ShadowRays_BareNp, scene, #scene)->Apply(threads); \
  BENCHMARK_CAPTURE(BM_ShadowRays_Build, scene, #scene)->Apply(threads);  \
  BENCHMARK_CAPTURE(BM_SceneBuild, scene, #scene)->Apply(threads)

SHADOW_RAY_CASES(ground_sphere);
SHADOW_RAY_CASES(stairs_room);
SHADOW_RAY_CASES(large_sphere);
BENCHMARK_CAPTURE(BM_ReferenceRender, ground_sphere, "ground_sphere")->Apply(threads);
BENCHMARK_CAPTURE(BM_ReferenceRender, stairs_room, "stairs_room")->Apply(threads);

}  // namespace

BENCHMARK_MAIN();
