// judge_bench.cpp — what the judge asks of the scene for each wrong pixel of a shadow map, timed
// alone: the cause model's explain() (reference/causes.hpp: the texel footprint and the depth bias,
// traced with Embree) over every wrong decided pixel of the reference's own mask shifted by 1 px, and
// the zigzag check (conform/zigzags.hpp) over a tile of it swapped at the boundary's busiest place
// (conform::swapped_tile, the resolving power's probe), on a catalogue scene at its own resolution
// under a 512-texel own map, where the check certifies grazing_light's tile. The reference is
// computed once, into a cache beside the binary. No peer: nothing else answers these questions, so
// the figures are times per pixel and per window, tracked but not judged (README.md).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/conform/resolving_power.hpp"
#include "shadowref/conform/zigzags.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/reference/causes.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace {

using namespace shadowref;

// A scene, its reference's light-0 mask and decided pixels, the declaration judged under, and its
// two mutants' wrong decided pixels.
struct Case {
  scene::Scene scene;
  scene::PreparedScene prepared;
  outputs::Image8 reference, decided, shifted, tile;
  std::vector<std::size_t> shifted_wrong, tile_wrong;
  outputs::CandidateDeclaration declared = outputs::default_declaration("shadowmap");

  explicit Case(const std::string& name)
      : scene(scene::load_scene(std::filesystem::path(SHADOWREF_SCENES_DIR) / (name + ".json"))), prepared(scene::prepare_scene(scene)) {
    const std::filesystem::path dir = conform::ensure_reference(prepared, SHADOWREF_BENCH_CACHE, {}).dir;
    const std::size_t lights = prepared.lights.size();
    reference = outputs::read_image8(dir / outputs::mask_name(0, lights), 1);
    decided = outputs::read_image8(dir / outputs::decided_name(0, lights), 1);
    shifted = conform::shifted(reference, 1, 0);
    tile = conform::swapped_tile(reference, 0);
    shifted_wrong = wrong_of(shifted);
    tile_wrong = wrong_of(tile);
    declared.shadow_map_size = 512;
    declared.light_views = outputs::LightViews::Own;
  }
  Case(const Case&) = delete;  // `prepared` points into `scene`

  std::vector<std::size_t> wrong_of(const outputs::Image8& candidate) const {
    std::vector<std::size_t> wrong;
    for (std::size_t i = 0; i < candidate.pixels.size(); ++i)
      if (decided.pixels[i] == 255 && candidate.pixels[i] != reference.pixels[i]) wrong.push_back(i);
    return wrong;
  }
};

Case& case_of(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Case>> cases;
  std::unique_ptr<Case>& c = cases[name];
  if (!c) c = std::make_unique<Case>(name);
  return *c;
}

// explain() of every wrong pixel of the 1-px shift, with the candidate's answer there; a fresh cause
// model each iteration (what one judged case builds), its construction included.
void BM_Explain(benchmark::State& state, const std::string& name) {
  Case& c = case_of(name);
  std::int64_t explained = 0;
  for (auto _ : state) {
    reference::CauseModel model(c.prepared);
    for (const std::size_t i : c.shifted_wrong) {
      const int x = static_cast<int>(i % static_cast<std::size_t>(c.shifted.width)), y = static_cast<int>(i / static_cast<std::size_t>(c.shifted.width));
      const outputs::Cause why = model.explain(0, x, y, c.declared, c.shifted.pixels[i] == outputs::kMaskLit);
      explained += why == outputs::Cause::TexelFootprint || why == outputs::Cause::DepthBias;
      benchmark::DoNotOptimize(why);
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(c.shifted_wrong.size()));
  state.counters["wrong_px"] = static_cast<double>(c.shifted_wrong.size());
  state.counters["explained_px"] = static_cast<double>(explained) / static_cast<double>(state.iterations());
  shadowref::bench::report_peak_rss(state);
}

// The zigzag check over the swapped tile: its windows, their stored samples, the certificates.
void BM_Zigzags(benchmark::State& state, const std::string& name) {
  Case& c = case_of(name);
  reference::CauseModel model(c.prepared);
  conform::ZigzagFinding found;
  for (auto _ : state) {
    found = conform::find_zigzags(model, c.prepared, 0, c.declared, c.reference, c.tile, c.tile_wrong);
    benchmark::DoNotOptimize(found.impossible.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(found.windows));
  state.counters["windows"] = static_cast<double>(found.windows);
  state.counters["judged_windows"] = static_cast<double>(found.judged);
  state.counters["impossible_px"] = static_cast<double>(found.impossible.size());
  shadowref::bench::report_peak_rss(state);
}

}  // namespace

// grazing_light: the check certifies its tile (81 px); directional_light: a tile it looks at and
// leaves alone.
BENCHMARK_CAPTURE(BM_Explain, grazing_light, std::string("grazing_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
BENCHMARK_CAPTURE(BM_Explain, directional_light, std::string("directional_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
BENCHMARK_CAPTURE(BM_Zigzags, grazing_light, std::string("grazing_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
BENCHMARK_CAPTURE(BM_Zigzags, directional_light, std::string("directional_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

BENCHMARK_MAIN();
