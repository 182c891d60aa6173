// declared_views_test.cpp — what a declaration of the light's views says is checked against the
// masks (docs/tolerance-model.md, "What a declaration may do"): a declared map size against the
// masks' own staircases, a swapped tile against the texel grids that could give it (zigzags),
// declared light matrices off by half a texel, turned or left-handed, texels longer along one
// axis, the counts and convention of declared matrices, and a cascade switch within the declared
// blend; each beside our correct render judged alike.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "grid_scene.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/reference/causes.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref {
namespace {

using namespace test;  // the grid's scene and mutations (grid_scene.hpp)

// A declared map size on the pack's grid is checked against the mask's own staircases
// (tolerance/staircases.hpp). Under grazing_light's sun 8 degrees up a 512-texel map's texel spans
// several pixels along the ground. Our render at 512 texels agrees with that declaration and PASSes;
// our finer render declared as 512 texels is contradicted, judged at the automatic size, and still
// PASSes (a correct render wrongly declared is still correct); the same render shifted by one pixel
// under that declaration FAILs — without the check the 512-texel footprint explained the shift.
TEST(Staircases, ADeclaredPackMapSizeIsCheckedAgainstTheMasksOwnStaircases) {
  SceneUnderTest s("grazing_light");
  const std::string at_512 = R"("slope_bias_texels": 2, "shadow_map_size": 512, "light_views": "pack")";
  renderer::RenderOptions options;
  options.shadow_map_size = 512;
  const renderer::RenderResult coarse = test::llvmpipe_renderer().render(s.scene, "shadowmap", options);
  ASSERT_EQ(coarse.declaration.shadow_map_size, 512);
  ASSERT_EQ(coarse.declaration.light_views, outputs::LightViews::Pack);
  const conform::CaseJudgement drawn = s.judged("staircases-512", coarse.masks.at(0), at_512);
  EXPECT_EQ(drawn.comparison.decision.verdict, compare::Verdict::Pass);
  EXPECT_NE(drawn.causes.find("512-texel map on the pack's grid is not contradicted"), std::string::npos) << drawn.causes;
  const conform::CaseJudgement finer = s.judged("staircases-finer", s.control, at_512);
  EXPECT_EQ(finer.comparison.decision.verdict, compare::Verdict::Pass) << "a correct render, wrongly declared";
  EXPECT_NE(finer.causes.find("is contradicted"), std::string::npos) << finer.causes;
  Image8 moved = s.control;
  shifted(1)(moved);
  const conform::CaseJudgement shift = s.judged("staircases-shifted", moved, at_512);
  EXPECT_NE(shift.causes.find("is contradicted"), std::string::npos) << shift.causes;
  EXPECT_EQ(shift.comparison.decision.verdict, compare::Verdict::Fail)
      << shift.comparison.total.unexplained << " px unexplained (" << 100 * shift.comparison.total.unexplained_ratio()
      << " % of the edges)";
}

// A tile swapped across grazing_light's long shadow edge (its busiest place) under a 512-texel map of
// the candidate's own views: every pixel of it lies within that map's footprint of the true edge
// (9 px a texel along the swap), but no texel grid gives them together — the edge would zigzag
// (tolerance/zigzags.hpp). The tile FAILs, and the pixels counted as zigzags all lie in it. Beside it,
// correct renders of that declaration — our map at 512 texels of our own views, turned and moved
// as an engine's fit turns and moves them, nearest and PCF — PASS with no pixel counted.
TEST(Zigzags, ASwappedTileFailsWhereEachPixelAloneIsExplained) {
  SceneUnderTest s("grazing_light");
  const std::string own_512 = R"("shadow_map_size": 512)";
  Image8 tile = s.control;
  swapped_tile(0)(tile);
  const conform::CaseJudgement j = s.judged("zigzag-tile", tile, own_512);
  EXPECT_EQ(j.comparison.decision.verdict, compare::Verdict::Fail);
  const compare::MaskMetrics& m = j.comparison.total;
  EXPECT_GT(m.unexplained_zigzag, compare::kLocalGlitch.densest_fail) << m.unexplained << " px unexplained";
  // Where they lie: each inside the swapped 16 x 8 pixels.
  const conform::CaseJudgement control = s.judged("zigzag-control", s.control, own_512);
  EXPECT_EQ(control.comparison.decision.verdict, compare::Verdict::Pass);
  EXPECT_EQ(control.comparison.total.unexplained_zigzag, 0u);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < tile.pixels.size(); ++i) changed += tile.pixels[i] != s.control.pixels[i];
  EXPECT_LE(m.unexplained_zigzag, changed) << "zigzag pixels outside the tile";
  for (const double turn : {0.0, 22.5, 45.0, -33.0})
    for (const char* technique : {"shadowmap", "shadowmap-pcf"}) {
      renderer::RenderOptions o;
      o.shadow_map_size = 512;
      o.view_turn_degrees = turn;
      o.view_phase_texels = 0.3;
      const renderer::RenderResult r = test::llvmpipe_renderer().render(s.scene, technique, o);
      ASSERT_EQ(r.declaration.light_views, outputs::LightViews::Own);
      nlohmann::json keys = nlohmann::json::parse(outputs::declaration_text(r.declaration));
      keys.erase("technique");
      const std::string declared = keys.dump().substr(1, keys.dump().size() - 2);
      const std::string name = std::string("zigzag-") + technique + "-turn-" + std::to_string(static_cast<int>(turn));
      const conform::CaseJudgement c = s.judged(name, r.masks.at(0), declared, 0, technique);
      EXPECT_NE(c.comparison.decision.verdict, compare::Verdict::Fail) << name;
      EXPECT_EQ(c.comparison.total.unexplained_zigzag, 0u) << name;
    }
}

// Declared light matrices are held to the mask's staircases as the pack's grid is: our grazing_light
// render at 512 texels with its exact matrices declared agrees with them and PASSes; the same render
// declaring matrices whose grid is moved by half a texel, or turned by 5 degrees about the view axis,
// is contradicted (the case's causes say so) and judged as the candidate's own views.
TEST(Staircases, DeclaredLightMatricesOffByHalfATexelOrTurnedAreReported) {
  SceneUnderTest s("grazing_light");
  renderer::RenderOptions options;
  options.shadow_map_size = 512;
  options.declare_light_matrices = true;
  const renderer::RenderResult r = test::llvmpipe_renderer().render(s.scene, "shadowmap", options);
  ASSERT_EQ(r.declaration.for_light(0).light_views, outputs::LightViews::Declared);
  ASSERT_EQ(r.declaration.for_light(0).views.size(), 1u);
  const auto judged_with = [&](const std::string& name, const Mat4<double>& clip_change) {
    outputs::CandidateDeclaration d = r.declaration;
    outputs::DeclaredView& v = d.lights.at(0).views.at(0);
    const Mat4<double> p = clip_change * Eigen::Map<const Mat4<double>>(v.projection.data());
    std::copy(p.data(), p.data() + 16, v.projection.begin());
    nlohmann::json keys = nlohmann::json::parse(outputs::declaration_text(d));
    keys.erase("technique");
    const std::string text = keys.dump();
    return s.judged(name, r.masks.at(0), text.substr(1, text.size() - 2));
  };
  const conform::CaseJudgement exact = judged_with("matrices-exact", Mat4<double>::Identity());
  EXPECT_EQ(exact.comparison.decision.verdict, compare::Verdict::Pass);
  EXPECT_NE(exact.causes.find("declared light matrices' grid is not contradicted"), std::string::npos) << exact.causes;
  Mat4<double> half_texel = Mat4<double>::Identity();
  half_texel(0, 3) = half_texel(1, 3) = 1.0 / 512;  // NDC spans 2 / 512 per texel
  const double a = 5 * std::acos(-1.0) / 180;
  Mat4<double> turned = Mat4<double>::Identity();
  turned(0, 0) = turned(1, 1) = std::cos(a);
  turned(0, 1) = -std::sin(a);
  turned(1, 0) = std::sin(a);
  for (const auto& [name, change] : {std::pair<std::string, Mat4<double>>{"half a texel", half_texel}, {"turned 5 degrees", turned}}) {
    const conform::CaseJudgement off = judged_with("matrices-" + name, change);
    EXPECT_NE(off.causes.find("declared light matrices' grid is contradicted"), std::string::npos) << name << ": " << off.causes;
    EXPECT_EQ(off.comparison.decision.verdict, compare::Verdict::Pass) << name << ": a correct render, wrongly declared";
  }
}

// A declared view may be left-handed in a right-handed run (Babylon.js draws its maps so): the same
// grid said with the view's z turned round (V' = F V, P' = P F, F = diag(1, 1, -1, 1), so P' V' = P V)
// is judged exactly as said right-handed — the judge reads which way is away from the light from the
// projection, for an orthographic view (grazing_light's sun) and a perspective one (spot_light's).
TEST(DeclaredMatrices, ALeftHandedViewOfTheSameGridIsJudgedAlike) {
  for (const char* name : {"grazing_light", "spot_light"}) {
    SceneUnderTest s(name);
    renderer::RenderOptions options;
    options.shadow_map_size = 512;
    options.declare_light_matrices = true;
    const renderer::RenderResult r = test::llvmpipe_renderer().render(s.scene, "shadowmap", options);
    ASSERT_EQ(r.declaration.for_light(0).light_views, outputs::LightViews::Declared) << name;
    const auto judged = [&](const std::string& label, bool left_handed) {
      outputs::CandidateDeclaration d = r.declaration;
      std::vector<outputs::DeclaredView*> views;
      for (outputs::DeclaredView& v : d.views) views.push_back(&v);
      for (outputs::CandidateDeclaration& light : d.lights)
        for (outputs::DeclaredView& v : light.views) views.push_back(&v);
      EXPECT_FALSE(views.empty());
      for (outputs::DeclaredView* v : views) {
        if (!left_handed) continue;
        const Mat4<double> flip = Vec4<double>(1, 1, -1, 1).asDiagonal();
        const Mat4<double> view = flip * Eigen::Map<const Mat4<double>>(v->view.data());
        const Mat4<double> projection = Eigen::Map<const Mat4<double>>(v->projection.data()) * flip;
        std::copy(view.data(), view.data() + 16, v->view.begin());
        std::copy(projection.data(), projection.data() + 16, v->projection.begin());
      }
      nlohmann::json keys = nlohmann::json::parse(outputs::declaration_text(d));
      keys.erase("technique");
      const std::string text = keys.dump();
      return s.judged(label, r.masks.at(0), text.substr(1, text.size() - 2));
    };
    const conform::CaseJudgement right = judged(std::string(name) + "-right-handed", false);
    const conform::CaseJudgement left = judged(std::string(name) + "-left-handed", true);
    EXPECT_EQ(right.comparison.decision.verdict, compare::Verdict::Pass) << name;
    EXPECT_EQ(left.comparison.decision.verdict, compare::Verdict::Pass) << name;
    EXPECT_NE(left.causes.find("declared light matrices' grid is not contradicted"), std::string::npos) << name << ": " << left.causes;
    EXPECT_EQ(left.comparison.total.unexplained, right.comparison.total.unexplained) << name;
    EXPECT_EQ(left.comparison.total.explained_texel, right.comparison.total.explained_texel) << name;
    EXPECT_EQ(left.comparison.total.explained_bias, right.comparison.total.explained_bias) << name;
  }
}

// Declared cascades that blend (Babylon.js mixes each cascade into the next over the far
// cascadeBlendPercentage of its depth range): a hard mask of a blend shows cascade i's answer or
// cascade i + 1's in that zone, so either may explain it. Our csm on sun_horizon (128-texel cascades,
// long shadows across the splits) switches at its splits; declared with each inner split moved
// later, by a fifth of the cascade's declared length, the zone between is drawn by the next cascade
// but declared to the earlier one. Declared with cascade_blend 0.25 it PASSes (measured: 5 px
// unexplained, the exact declaration 0); declared without the blend those pixels are left to the
// earlier cascade's finer texels (19 px unexplained).
TEST(DeclaredCascades, ASwitchWithinTheDeclaredBlendIsExplainedByEitherCascade) {
  const scene::Scene scene = scene::load_scene(conform::default_catalogue() / "sun_horizon.json");
  scene::PrepareOptions prepare;
  prepare.shadow_map_size = 128;  // cascades coarse enough that the next one's staircases differ
  const scene::PreparedScene prepared = scene::prepare_scene(scene, kDefaultConvention, prepare);
  conform::ReferenceSettings settings;
  settings.key_executable = SHADOWREF_EXE;
  const fs::path reference = conform::ensure_reference(prepared, SHADOWREF_TEST_CACHE, settings).dir;
  renderer::RenderOptions options;
  options.declare_light_matrices = true;
  const renderer::RenderResult r = test::llvmpipe_renderer().render(prepared, "csm", options);
  const std::vector<double> drawn = r.declaration.for_light(0).cascade_splits;
  ASSERT_GE(drawn.size(), 3u) << "csm declares its cascades' splits";
  // s'[i+1] − s[i+1] = 0.2 (s'[i+1] − s'[i]): the drawn split lies a fifth of the declared cascade
  // before its declared end. The first and the last split stay.
  std::vector<double> later = drawn;
  for (std::size_t i = 1; i + 1 < drawn.size(); ++i) later[i] = std::min((drawn[i] - 0.2 * later[i - 1]) / 0.8, 0.5 * (drawn[i] + drawn[i + 1]));
  conform::Judge judge{false};  // verdicts only: no resolving power
  const auto judged = [&](const std::string& name, const std::vector<double>& splits, double blend) {
    outputs::CandidateDeclaration d = r.declaration;
    for (outputs::CandidateDeclaration* l : {&d, d.lights.empty() ? &d : &d.lights.at(0)})
      if (!l->cascade_splits.empty()) {
        l->cascade_splits = splits;
        l->cascade_blend = blend;
      }
    const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / "declared-cascades" / name;
    fs::create_directories(dir);
    outputs::write_png(r.masks.at(0), dir / "mask.png");
    outputs::write_declaration(d, dir);
    const conform::CaseJudgement j = judge.judge(&prepared, {reference, dir, "csm", false, {}});
    const compare::MaskMetrics& m = j.comparison.total;
    std::printf("sun_horizon csm at 128 texels, %s: %s, %zu px unexplained (%.2f %% of %zu edge px, core %zu), %zu explained\n",
                name.c_str(), compare::to_string(j.comparison.decision.verdict), m.unexplained, 100 * m.unexplained_ratio(),
                m.edge_pixels, m.unexplained_core, m.explained_texel);
    return j;
  };
  const conform::CaseJudgement exact = judged("exact", drawn, 0);
  const conform::CaseJudgement blended = judged("later-splits-blend-0.25", later, 0.25);
  const conform::CaseJudgement hard = judged("later-splits-no-blend", later, 0);
  EXPECT_EQ(exact.comparison.decision.verdict, compare::Verdict::Pass);
  EXPECT_EQ(blended.comparison.decision.verdict, compare::Verdict::Pass);
  EXPECT_GT(hard.comparison.total.unexplained, blended.comparison.total.unexplained)
      << "without the blend the moved switch is judged on the earlier cascade's texels";
}

// A declared view's texels need not be square (Babylon.js fits each cascade an off-centre box of
// its own aspect). The receiver's own plane, d texels away, is nearer by d texels of its slope —
// measured along the offset's own axis: on a view whose texels are 10 % longer along y than along x,
// a probe along y that counted x texels read the grazing ground itself as an occluder, and all
// 55 163 lit pixels of grazing_light, made false shadow, came out "texel footprint" (Babylon.js's
// cascades on offscreen_caster: 25 445 px of acne explained). Now only a band along the true
// shadow's edges is (158 px).
TEST(DeclaredMatrices, TexelsLongerAlongOneAxisDoNotExplainAcne) {
  const test::CatalogueScene sun("grazing_light");
  renderer::RenderOptions options;
  options.shadow_map_size = 1024;
  options.declare_light_matrices = true;
  const renderer::RenderResult r = test::llvmpipe_renderer().render(sun.prepared, "shadowmap", options);
  ASSERT_EQ(r.declaration.for_light(0).light_views, outputs::LightViews::Declared);
  ASSERT_EQ(r.declaration.for_light(0).views.size(), 1u);
  const Image8 mask = outputs::read_image8(sun.reference / "mask.png", 1);
  const Image8 decided = outputs::read_image8(sun.reference / "decided.png", 1);
  reference::CauseModel model(sun.prepared);
  // The view turned by 0 and 90 degrees about its axis (so that the ground's slope runs along
  // either texel axis), then its texels made 10 % longer along y.
  for (const int degrees : {0, 90}) {
    outputs::CandidateDeclaration d = r.declaration.for_light(0);
    d.lights.clear();
    const double a = degrees * std::acos(-1.0) / 180;
    Mat4<double> change = Mat4<double>::Identity();
    change(0, 0) = change(1, 1) = std::cos(a);
    change(0, 1) = -std::sin(a);
    change(1, 0) = std::sin(a);
    change.row(1) /= 1.1;
    const Mat4<double> p = change * Eigen::Map<const Mat4<double>>(d.views[0].projection.data());
    std::copy(p.data(), p.data() + 16, d.views[0].projection.begin());
    std::size_t lit = 0, footprint = 0;
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * mask.width + x);
        if (mask.pixels[i] != kMaskLit || !outputs::is_flag_set(decided.pixels[i])) continue;
        ++lit;
        footprint += model.explain(0, x, y, d, false) == outputs::Cause::TexelFootprint;
      }
    std::printf("grazing_light, false shadow on every lit pixel, view turned %d degrees, texels 1.1 times longer "
                "along y: %zu of %zu explained by the footprint\n", degrees, footprint, lit);
    ASSERT_GT(lit, 1000u);
    EXPECT_LT(footprint, lit / 20) << degrees << " degrees: only a band along the shadow's edges";
  }
}

// Declared matrices the scene cannot have been drawn with are bad input, named by their JSON path:
// two views for a point light (1, or a cube's 6), a view missing, or matrices in another convention
// than the run's (they are read in the run's).
TEST(DeclaredMatrices, TheCountsAndTheConventionAreChecked) {
  SceneUnderTest s("two_lights");
  const std::string view = R"({"view": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,-5,1], "projection": [1,0,0,0, 0,1,0,0, 0,0,-1,-1, 0,0,-0.2,0]})";
  const auto refused = [&](const std::string& name, const std::string& keys) -> std::string {
    try {
      s.judged(name, s.control, keys);
    } catch (const outputs::InputError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_NE(refused("two-views", R"("shadow_map_size": 512, "light_views": "declared", "lights": [{"views": [)" + view + ", " + view +
                                     "]}, {\"views\": [" + view + "]}]")
                .find("lights[0].views: a point or spot light has 1 view or a cube's 6"),
            std::string::npos);
  EXPECT_NE(refused("no-views", R"("shadow_map_size": 512, "light_views": "declared", "lights": [{"views": [)" + view + "]}]")
                .find("views: light_views \"declared\" needs this light's views"),
            std::string::npos)
      << "light 1 takes the top level, which declares no views";
  EXPECT_NE(refused("d3d", R"("convention": "d3d", "shadow_map_size": 512, "light_views": "declared", "views": [)" + view + "]")
                .find("convention: declared light matrices are read in the run's convention 'gl'"),
            std::string::npos);
}

}  // namespace
}  // namespace shadowref
