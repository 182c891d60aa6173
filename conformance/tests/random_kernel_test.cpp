// random_kernel_test.cpp — a randomized kernel is judged fairly, and its faults still fail
// (docs/tolerance-model.md, "Randomized kernels"). Our renderer's pcss and shadowmap-pcf with N taps
// of a Vogel disk turned per pixel by noise (renderer::RenderOptions::random_taps), declared
// "sampling": "random" with light_taps sqrt(N), PASS; the same renders with one soft or shadow-map
// fault on (the teeth's faults: a light of half or twice the size, the blocker search reading the
// receiver, no polygon offset) FAIL under that same declaration. The whole catalogue at 64 taps is
// the sweep conformance.sweep.random-kernel; this test holds the controls and their faults side by side.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "catalogue_scene.hpp"
#include "llvmpipe_renderer.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;
using renderer::Faults;

struct Variant {
  const char* name;
  std::function<void(Faults&)> fault;  // none: the control
};

// Renders `technique` on `scene_name` with `taps` random taps and `variant`'s fault, and judges it
// under the renderer's own (honest) declaration.
conform::CaseJudgement render_and_judge(const std::string& scene_name, const std::string& technique, int taps,
                                        const Variant& variant) {
  const test::CatalogueScene c(scene_name);
  const scene::Scene& scene = c.scene;
  const scene::PreparedScene& prepared = c.prepared;
  const fs::path& reference = c.reference;
  renderer::RenderOptions options;
  options.random_taps = taps;
  if (variant.fault) variant.fault(options.faults);
  const renderer::RenderResult r = test::llvmpipe_renderer().render(prepared, technique, options);
  EXPECT_EQ(r.declaration.sampling, outputs::Sampling::Random);
  EXPECT_EQ(r.declaration.light_taps * r.declaration.light_taps, taps) << "light_taps is the root of the taps";
  const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / scene_name / technique / (std::to_string(taps) + "-" + variant.name);
  renderer::write_outputs(r, test::llvmpipe_renderer().info(), scene, dir);
  conform::Judge judge{false};  // verdicts only: no resolving power
  conform::CaseJudgement j = judge.judge(&prepared, {reference, dir, technique, true, {}});
  const compare::Decision& v = j.comparison.decision;
  std::printf("%s x %s, %d random taps, %s: %s", scene_name.c_str(), technique.c_str(), taps, variant.name,
              compare::to_string(v.verdict));
  if (j.comparison.visibility_total)
    std::printf(" (lit fraction: mean error %.3f, local means %.3f)", j.comparison.visibility_total->mean_penumbra_error(),
                j.comparison.visibility_total->mean_penumbra_local_error());
  std::printf("\n");
  for (const std::string& reason : v.reasons) std::printf("  %s\n", reason.c_str());
  return j;
}

class RandomKernel : public ::testing::TestWithParam<int> {};

// soft_penumbra: a rect light over a plate and a ball, the penumbra the soft techniques exist for.
TEST_P(RandomKernel, PcssPassesAndItsFaultsFailOnTheSoftPenumbra) {
  const int taps = GetParam();
  EXPECT_EQ(render_and_judge("soft_penumbra", "pcss", taps, {"control", {}}).comparison.decision.verdict,
            compare::Verdict::Pass);
  for (const Variant& v : {Variant{"half-light-size", [](Faults& f) { f.soft.light_size_scale = 0.5; }},
                           Variant{"twice-light-size", [](Faults& f) { f.soft.light_size_scale = 2.0; }},
                           Variant{"blocker-at-receiver", [](Faults& f) { f.soft.blocker_depth_from_receiver = true; }}})
    EXPECT_EQ(render_and_judge("soft_penumbra", "pcss", taps, v).comparison.decision.verdict, compare::Verdict::Fail)
        << v.name << " with " << taps << " random taps";
}

// directional_light: flat ground under a sun, where a missing bias shows as acne.
TEST_P(RandomKernel, PcfPassesAndItsAcneFailsUnderTheSun) {
  const int taps = GetParam();
  EXPECT_EQ(render_and_judge("directional_light", "shadowmap-pcf", taps, {"control", {}}).comparison.decision.verdict,
            compare::Verdict::Pass);
  const Variant acne{"no-polygon-offset", [](Faults& f) { f.shadow_map.no_polygon_offset = true; }};
  EXPECT_EQ(render_and_judge("directional_light", "shadowmap-pcf", taps, acne).comparison.decision.verdict,
            compare::Verdict::Fail);
}

// 16 taps (4 per axis: the noisiest an engine commonly ships) and 64 (our grid's count).
INSTANTIATE_TEST_SUITE_P(Taps, RandomKernel, ::testing::Values(16, 64),
                         [](const ::testing::TestParamInfo<int>& i) { return std::to_string(i.param) + "_taps"; });

}  // namespace
}  // namespace shadowref
