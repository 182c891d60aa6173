// judge_bench.cpp — what the judge asks of the scene for each wrong pixel of a shadow map, timed
// alone: the cause model's explain() (reference/causes.hpp: the texel footprint and the depth bias,
// traced with Embree) over every wrong decided pixel of the reference's own mask shifted by 1 px, and
// the zigzag check (tolerance/zigzags.hpp) over a tile of it swapped at the boundary's busiest place
// (tolerance::swapped_tile, the resolving power's probe), on a catalogue scene at its own resolution
// under a 512-texel own map, where the check certifies grazing_light's tile. The reference is
// computed once, into a cache beside the binary. No peer: nothing else answers these questions, so
// the figures are times per pixel and per window, tracked but not judged (README.md).
//
// BM_JudgeCase times one whole case as `shadowref conform` judges it (conform::Judge: the
// declaration, the comparison with its causes, the resolving power's probes, the status) at the
// scene's 256² and at 1920 x 1080, the candidate the reference's own masks shifted by 1 px (the
// boundary errors of a correct map) declared as a 512-texel map of its own views; a fresh Judge
// each iteration, so that nothing a previous case asked is remembered. BM_JudgeCase_Floor is the
// same folders compared with no cause model and no probes (compare_folders under the exact
// threshold: reading the masks and one pass over them), what judging cannot go below.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "shadowref/compare/thresholds.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/tolerance/zigzags.hpp"
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
    shifted = tolerance::shifted(reference, 1, 0);
    tile = tolerance::swapped_tile(reference, 0);
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
  tolerance::ZigzagFinding found;
  for (auto _ : state) {
    found = tolerance::find_zigzags(model, c.prepared, 0, c.declared, c.reference, c.tile, c.tile_wrong);
    benchmark::DoNotOptimize(found.impossible.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(found.windows));
  state.counters["windows"] = static_cast<double>(found.windows);
  state.counters["judged_windows"] = static_cast<double>(found.judged);
  state.counters["impossible_px"] = static_cast<double>(found.impossible.size());
  shadowref::bench::report_peak_rss(state);
}

// A candidate folder beside the reference of `name` at `width` x `height`: every light's mask
// shifted by 1 px right, declared as a 512-texel map of the candidate's own views.
struct JudgedCase {
  scene::Scene scene;
  scene::PreparedScene prepared;
  std::filesystem::path reference_dir, candidate_dir;

  JudgedCase(const std::string& name, int width, int height)
      : scene(sized(scene::load_scene(std::filesystem::path(SHADOWREF_SCENES_DIR) / (name + ".json")), width, height)),
        prepared(scene::prepare_scene(scene)) {
    reference_dir = conform::ensure_reference(prepared, SHADOWREF_BENCH_CACHE, {}).dir;
    candidate_dir = std::filesystem::path(SHADOWREF_BENCH_CACHE) / ("candidate-" + name + "-" + std::to_string(width) + "x" + std::to_string(height));
    std::filesystem::create_directories(candidate_dir);
    const std::size_t lights = prepared.lights.size();
    for (std::size_t i = 0; i < lights; ++i)
      outputs::write_png(tolerance::shifted(outputs::read_image8(reference_dir / outputs::mask_name(i, lights), 1), 1, 0),
                         candidate_dir / outputs::mask_name(i, lights));
    outputs::CandidateDeclaration d = outputs::default_declaration("shadowmap");
    d.shadow_map_size = 512;
    d.light_views = outputs::LightViews::Own;
    outputs::write_declaration(d, candidate_dir);
  }
  JudgedCase(const JudgedCase&) = delete;  // `prepared` points into `scene`

  static scene::Scene sized(scene::Scene s, int width, int height) {
    s.width = width;
    s.height = height;
    return s;
  }
};

JudgedCase& judged_case(const std::string& name, int width, int height) {
  static std::map<std::string, std::unique_ptr<JudgedCase>> cases;
  std::unique_ptr<JudgedCase>& c = cases[name + std::to_string(width) + "x" + std::to_string(height)];
  if (!c) c = std::make_unique<JudgedCase>(name, width, height);
  return *c;
}

void BM_JudgeCase(benchmark::State& state, const std::string& name) {
  JudgedCase& c = judged_case(name, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  std::size_t unexplained = 0;
  for (auto _ : state) {
    conform::Judge judge;  // a new case: nothing remembered
    const conform::CaseJudgement j = judge.judge(&c.prepared, {c.reference_dir, c.candidate_dir, "shadowmap", false, {}});
    unexplained = j.comparison.total.unexplained;
    benchmark::DoNotOptimize(j.status);
  }
  state.counters["pixels"] = static_cast<double>(state.range(0) * state.range(1));
  state.counters["unexplained_px"] = static_cast<double>(unexplained);
  shadowref::bench::report_peak_rss(state);
}

void BM_JudgeCase_Floor(benchmark::State& state, const std::string& name) {
  JudgedCase& c = judged_case(name, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) {
    const compare::FolderComparison f = compare::compare_folders(c.reference_dir, c.candidate_dir, compare::threshold_for("planar"));
    benchmark::DoNotOptimize(f.total.wrong);
  }
  state.counters["pixels"] = static_cast<double>(state.range(0) * state.range(1));
  shadowref::bench::report_peak_rss(state);
}

}  // namespace

// At the scene's own 256² and at an engine's 1920 x 1080 (its reference computed once, into the cache).
BENCHMARK_CAPTURE(BM_JudgeCase, directional_light, std::string("directional_light"))->Args({256, 256})->Args({1920, 1080})
    ->ArgNames({"w", "h"})->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
BENCHMARK_CAPTURE(BM_JudgeCase_Floor, directional_light, std::string("directional_light"))->Args({256, 256})->Args({1920, 1080})
    ->ArgNames({"w", "h"})->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

// grazing_light: the check certifies its tile (81 px); directional_light: a tile it looks at and
// leaves alone.
BENCHMARK_CAPTURE(BM_Explain, grazing_light, std::string("grazing_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
BENCHMARK_CAPTURE(BM_Explain, directional_light, std::string("directional_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
BENCHMARK_CAPTURE(BM_Zigzags, grazing_light, std::string("grazing_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);
BENCHMARK_CAPTURE(BM_Zigzags, directional_light, std::string("directional_light"))->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

BENCHMARK_MAIN();
