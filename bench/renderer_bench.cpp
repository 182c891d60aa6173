// renderer_bench.cpp — time per frame of every technique of the OpenGL renderer on three catalogue
// scenes at 512² and 1024², on Mesa's llvmpipe through OSMesa, rasterising in the calling thread
// (the renderer sets LP_NUM_THREADS=0: docs/architecture.md, "The GL context").
// The time is the renderer's own frame time (RenderResult::frame_ms: every pass to glFinish and
// the read-back), reported as manual time; pixels_per_s counts the frame's pixels. What depends on
// the scene alone (casters, adjacency, light fitting) is in the prepared scene, built once.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "bench_support.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace {

namespace rnd = shadowref::renderer;

rnd::Renderer& renderer() {
  static rnd::Renderer r(rnd::GlApi::OSMesa, rnd::Driver::Llvmpipe);
  return r;
}

void BM_Frame(benchmark::State& state, const std::string& scene_name, const std::string& technique) {
  auto scene = shadowref::scene::load_scene(std::string(SHADOWREF_SCENES_DIR) + "/" + scene_name + ".json");
  const auto side = static_cast<int>(state.range(0));
  scene.width = scene.height = side;
  // Load-time work (casters, adjacency, light fitting) once, outside every frame.
  const shadowref::scene::PreparedScene prepared = shadowref::scene::prepare_scene(scene);
  for (auto _ : state) {
    const rnd::RenderResult res = renderer().render(prepared, technique);
    state.SetIterationTime(res.frame_ms.front() / 1000.0);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * side * side);
  state.counters["pixels_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * side * side, benchmark::Counter::kIsRate);
  shadowref::bench::report_peak_rss(state);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (const char* scene : {"ground_sphere", "stairs_room", "torus_self_shadow"})
    for (const auto& t : rnd::techniques())
      benchmark::RegisterBenchmark(("BM_Frame/" + std::string(scene) + "/" + std::string(t.name)).c_str(), BM_Frame,
                                   std::string(scene), std::string(t.name))
          ->Arg(512)->Arg(1024)->ArgName("px")->UseManualTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
