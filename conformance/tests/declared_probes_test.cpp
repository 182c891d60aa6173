// declared_probes_test.cpp — a declaration reaches what it names and nothing else: the judge's
// resolving power is probed under the declaration as judged (a cascaded technique with its
// cascades, not a cached single map's), and a per-light entry in candidate.json judges its own
// light only and buys nothing there either.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <string>

#include "grid_scene.hpp"

namespace shadowref {
namespace {

using namespace test;  // the grid's scene and mutations (grid_scene.hpp)

// The judge keeps one resolving power per reference, threshold and declaration as judged. A
// cascaded technique declares "cascades": 0 for its default count, so csm-pcf's declaration reads
// as shadowmap-pcf's but for the technique's name, which the cause model reads (it looks a point up
// in its cascade): on sun_horizon the two differ at the reference's third tile, which one 2048-texel
// map's texel spans and a cascade's does not. A judge that has probed shadowmap-pcf must still give
// csm-pcf what a judge that never saw shadowmap-pcf gives it.
TEST(ResolvingPowerCache, ACascadedTechniqueIsProbedWithItsCascades) {
  const test::CatalogueScene sun("sun_horizon");
  const auto judged_as = [&](conform::Judge& judge, const char* technique) {
    const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / "resolving-power-cache" / technique;
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(sun.reference / "mask.png", dir / "mask.png");  // the truth itself: a correct render
    std::ofstream(dir / "candidate.json") << "{\"technique\": \"" << technique << "\", \"filter_radius_texels\": 1, "
                                          << "\"slope_bias_texels\": 3, \"light_views\": \"pack\"}\n";
    const conform::CaseJudgement j = judge.judge(&sun.prepared, {sun.reference, dir, "", false, {}});
    EXPECT_EQ(j.comparison.decision.verdict, compare::Verdict::Pass) << technique;
    return j.resolving_power.value();
  };
  const auto tiles = [](const tolerance::ResolvingPower& r) {
    std::string s;
    for (const tolerance::Probe& p : r.probes)
      if (p.kind == tolerance::ProbeKind::Tile8) s += p.name + ": " + compare::to_string(p.verdict) + ", " + std::to_string(p.unexplained) + " unexplained\n";
    return s;
  };
  conform::Judge fresh;
  const tolerance::ResolvingPower alone = judged_as(fresh, "csm-pcf");
  conform::Judge shared;
  const tolerance::ResolvingPower map = judged_as(shared, "shadowmap-pcf");
  const tolerance::ResolvingPower after = judged_as(shared, "csm-pcf");
  std::printf("shadowmap-pcf's tiles:\n%scsm-pcf's, alone:\n%scsm-pcf's, after shadowmap-pcf:\n%s", tiles(map).c_str(),
              tiles(alone).c_str(), tiles(after).c_str());
  // The two techniques' probes differ here, so that the cache's key is what is being tested.
  ASSERT_NE(tiles(map), tiles(alone));
  EXPECT_EQ(tiles(after), tiles(alone));
  EXPECT_EQ(after.summary(), alone.summary());
}

// Per-light declarations ("lights" in candidate.json) reach their own light only, and buy nothing
// there either: on two_lights (two point lights over a ground), our correct masks with an entry for
// light 1 only judge light 0 as without it; light 1's mask made all shadowed FAILs under the largest
// declaration the entry can make.
TEST(PerLightDeclarations, AnEntryReachesItsLightAndBuysNothing) {
  const test::CatalogueScene two_lights("two_lights");
  const scene::PreparedScene& prepared = two_lights.prepared;
  const fs::path& reference = two_lights.reference;
  const renderer::RenderResult ours = test::llvmpipe_renderer().render(prepared, "shadowmap");
  ASSERT_EQ(ours.masks.size(), 2u);
  conform::Judge judge{false};  // verdicts only: no resolving power
  const auto judged = [&](const std::string& name, const Image8& mask_0, const Image8& mask_1, const std::string& keys) {
    const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / "per-light" / name;
    fs::create_directories(dir);
    outputs::write_png(mask_0, dir / "mask_0.png");
    outputs::write_png(mask_1, dir / "mask_1.png");
    std::ofstream(dir / "candidate.json") << R"({"technique": "shadowmap", "slope_bias_texels": 2, "light_views": "pack")"
                                          << keys << "}\n";
    return judge.judge(&prepared, {reference, dir, "", false, {}});
  };
  const std::string largest = R"("slope_bias_texels": 8, "constant_bias": 1.0, "normal_offset_texels": 4, )"
                              R"("depth_bias": 0.01, "filter_radius_texels": 8, "light_views": "own", "shadow_map_size": 512)";
  const std::string entry_for_1 = R"(, "lights": [{}, {)" + largest + "}]";
  // Our masks: PASS with or without the entry.
  EXPECT_EQ(judged("plain", ours.masks[0], ours.masks[1], "").comparison.decision.verdict, compare::Verdict::Pass);
  EXPECT_EQ(judged("entry", ours.masks[0], ours.masks[1], entry_for_1).comparison.decision.verdict, compare::Verdict::Pass);
  // Both masks shifted by a pixel: light 0 is judged the same with or without light 1's entry, and
  // light 1 under its entry (the larger footprint explains more of its shift).
  Image8 shifted_0 = ours.masks[0], shifted_1 = ours.masks[1];
  shifted(1)(shifted_0);
  shifted(1)(shifted_1);
  const conform::CaseJudgement plain = judged("shifted-plain", shifted_0, shifted_1, "");
  const conform::CaseJudgement entry = judged("shifted-entry", shifted_0, shifted_1, entry_for_1);
  const compare::MaskMetrics& p0 = plain.comparison.per_light.at(0).metrics;
  const compare::MaskMetrics& e0 = entry.comparison.per_light.at(0).metrics;
  const compare::MaskMetrics& p1 = plain.comparison.per_light.at(1).metrics;
  const compare::MaskMetrics& e1 = entry.comparison.per_light.at(1).metrics;
  std::printf("two_lights shifted 1 px, explained by the footprint: light 0 %zu / %zu, light 1 %zu / %zu (plain / entry)\n",
              p0.explained_texel, e0.explained_texel, p1.explained_texel, e1.explained_texel);
  EXPECT_EQ(e0.unexplained, p0.unexplained) << "light 0 has no entry: judged as without one";
  EXPECT_EQ(e0.explained_texel, p0.explained_texel);
  EXPECT_GT(e1.explained_texel, p1.explained_texel) << "light 1 is judged under its entry";
  Image8 dark = ours.masks[1];
  for_surface(dark, [](std::uint8_t& v) { v = kMaskShadowed; });
  const conform::CaseJudgement bought = judged("all-shadowed", ours.masks[0], dark, entry_for_1);
  EXPECT_EQ(bought.comparison.decision.verdict, compare::Verdict::Fail)
      << bought.comparison.per_light.at(1).metrics.unexplained << " px unexplained on light 1";
}

}  // namespace
}  // namespace shadowref
