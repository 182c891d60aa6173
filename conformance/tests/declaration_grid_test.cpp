// declaration_grid_test.cpp — no declaration buys a verdict (docs/tolerance-model.md, "What a
// declaration may do"): our own correct shadow-map render of a scene is the control, judged by the
// one judge (conform/judge.hpp) under its honest declaration (PASS); then blatant mutants of its mask
// — all shadowed, all lit, inverted, shifted by 1 and 2 px, the shadow grown and shrunk by 1 and 2 px,
// a swapped 8 × 8 tile — are judged under every declaration of a grid (slope bias 0 … 8 texels,
// constant bias 0 … a scene-sized metre, normal offset, window-depth bias, filter radius 0 … 8,
// `pack` / `own`, maps of 512 … 4096 texels, and all of the largest at once, a randomized kernel of
// one tap among them): each must FAIL. And declaring less (a smaller bias, a smaller filter, `pack`
// for `own`) never explains more: the unexplained count and the verdict of every mask, control
// included, never improve along a chain of ever smaller declarations.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "catalogue_scene.hpp"
#include "llvmpipe_renderer.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/conform/resolving_power.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/reference/causes.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;
using outputs::Image8;
using outputs::kMaskLit;
using outputs::kMaskNoSurface;
using outputs::kMaskShadowed;

// A mutant: the control mask with one blatant defect. Surface pixels only: a mutant never changes
// coverage (that would fail on its own, whatever the shadows).
using Mutation = std::function<void(Image8&)>;

void for_surface(Image8& m, const std::function<void(std::uint8_t&)>& f) {
  for (std::uint8_t& v : m.pixels)
    if (v != kMaskNoSurface) f(v);
}

// Every surface pixel takes the answer of the one `dx` to its left (silhouettes stay put): the
// resolving power's shift probe, conform::shifted.
Mutation shifted(int dx) {
  return [dx](Image8& m) { m = conform::shifted(m, dx, 0); };
}

// The shadow grown (or, with `grow` false, shrunk) by `n` px: a surface pixel takes the answer
// `grow ? shadowed : lit` when any surface pixel within n px (a square) has it.
Mutation morphed(int n, bool grow) {
  return [n, grow](Image8& m) {
    const Image8 was = m;
    const std::uint8_t into = grow ? kMaskShadowed : kMaskLit;
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        std::uint8_t& v = m.pixels[static_cast<std::size_t>(y * m.width + x)];
        if (v == kMaskNoSurface) continue;
        for (int dy = -n; dy <= n && v != into; ++dy)
          for (int dx = -n; dx <= n; ++dx) {
            const int u = x + dx, w = y + dy;
            if (u < 0 || w < 0 || u >= m.width || w >= m.height) continue;
            if (was.pixels[static_cast<std::size_t>(w * m.width + u)] == into) {
              v = into;
              break;
            }
          }
      }
  };
}

// An 8 x 8 tile swapped with the one 8 px to its right, at the `rank`-th busiest place (the
// resolving power's probe, conform::swapped_tile).
Mutation swapped_tile(int rank) {
  return [rank](Image8& m) { m = conform::swapped_tile(m, rank); };
}

struct Mutant {
  const char* name;
  Mutation mutate;
};

std::vector<Mutant> mutants() {
  return {
      {"all-shadowed", [](Image8& m) { for_surface(m, [](std::uint8_t& v) { v = kMaskShadowed; }); }},
      {"all-lit", [](Image8& m) { for_surface(m, [](std::uint8_t& v) { v = kMaskLit; }); }},
      {"inverted", [](Image8& m) { for_surface(m, [](std::uint8_t& v) { v = v == kMaskLit ? kMaskShadowed : kMaskLit; }); }},
      {"shifted-1px", shifted(1)},
      {"shifted-2px", shifted(2)},
      {"grown-1px", morphed(1, true)},
      {"grown-2px", morphed(2, true)},
      {"shrunk-1px", morphed(1, false)},
      {"shrunk-2px", morphed(2, false)},
      {"swapped-tile", swapped_tile(0)},
      {"swapped-tile-2nd", swapped_tile(1)},
      {"swapped-tile-3rd", swapped_tile(2)},
      // Where no tile probe was put: the place farthest from the three (conform::tile_places), one
      // the resolving power's sweep alone speaks for.
      {"swapped-tile-held-out", swapped_tile(static_cast<int>(conform::kBusiestTilePlaces))},
  };
}

// A declaration: candidate.json's bias and footprint keys over the technique (shadowmap).
struct Declaration {
  std::string name;
  std::string json;  // the keys beyond "technique"
};

// Stands for our render's own declaration with its light matrices ("light_views": "declared", the
// exact views and projections the maps were drawn with): SceneUnderTest::judged fills it in.
constexpr const char* kOurMatrices = "@declared";

// The grid: each key at its extremes, then all the largest at once.
std::vector<Declaration> grid() {
  return {
      {"ours", R"("slope_bias_texels": 2, "light_views": "pack")"},
      {"declared", kOurMatrices},
      {"slope-0", R"("slope_bias_texels": 0, "light_views": "pack")"},
      {"slope-0-own", R"("slope_bias_texels": 0, "light_views": "own")"},
      {"slope-8", R"("slope_bias_texels": 8)"},
      {"constant-6.4cm", R"("slope_bias_texels": 0, "constant_bias": 0.064)"},
      {"constant-1m", R"("constant_bias": 1.0)"},
      {"normal-offset-4-texels", R"("normal_offset_texels": 4)"},
      {"depth-bias-1%", R"("depth_bias": 0.01)"},
      {"distance-bias-1m", R"("depth": "distance", "depth_bias": 0.1, "depth_range": 10, "slope_bias_texels": 0)"},
      {"filter-8", R"("filter_radius_texels": 8)"},
      {"map-512", R"("shadow_map_size": 512)"},
      {"map-512-pack", R"("shadow_map_size": 512, "light_views": "pack")"},
      {"map-4096-pack", R"("shadow_map_size": 4096, "light_views": "pack")"},
      {"largest", R"("slope_bias_texels": 8, "constant_bias": 1.0, "normal_offset_texels": 4, "depth_bias": 0.01, )"
                  R"("filter_radius_texels": 8, "light_views": "own", "shadow_map_size": 512, "sampling": "random", )"
                  R"("light_taps": 1)"},
  };
}

// Chains of ever smaller declarations (each entry declares less than the one before).
std::vector<std::vector<Declaration>> chains() {
  return {
      {{"slope 8", R"("slope_bias_texels": 8)"}, {"slope 2", R"("slope_bias_texels": 2)"}, {"slope 0", R"("slope_bias_texels": 0)"}},
      {{"constant 1 m", R"("constant_bias": 1.0, "slope_bias_texels": 0)"},
       {"constant 6.4 cm", R"("constant_bias": 0.064, "slope_bias_texels": 0)"},
       {"constant 0", R"("constant_bias": 0, "slope_bias_texels": 0)"}},
      {{"normal offset 4 texels", R"("normal_offset_texels": 4, "slope_bias_texels": 0)"},
       {"normal offset 0", R"("normal_offset_texels": 0, "slope_bias_texels": 0)"}},
      {{"depth bias 1 %", R"("depth_bias": 0.01, "slope_bias_texels": 0)"}, {"depth bias 0", R"("depth_bias": 0, "slope_bias_texels": 0)"}},
      {{"distance bias 1 m", R"("depth": "distance", "depth_range": 10, "depth_bias": 0.1, "slope_bias_texels": 0)"},
       {"distance bias 6.4 cm", R"("depth": "distance", "depth_range": 10, "depth_bias": 0.0064, "slope_bias_texels": 0)"},
       {"distance bias 0", R"("depth": "distance", "depth_range": 10, "depth_bias": 0, "slope_bias_texels": 0)"}},
      {{"filter 8", R"("filter_radius_texels": 8)"}, {"filter 1", R"("filter_radius_texels": 1)"}, {"filter 0", R"("filter_radius_texels": 0)"}},
      {{"own", R"("light_views": "own")"}, {"pack", R"("light_views": "pack")"}},
      {{"own", R"("light_views": "own")"}, {"declared", kOurMatrices}},
      {{"map 512 own", R"("shadow_map_size": 512, "light_views": "own")"},
       {"map 512 pack", R"("shadow_map_size": 512, "light_views": "pack")"}},
  };
}

// One scene: its prepared form, the reference (from the CTest fixtures' cache), our render's masks.
struct SceneUnderTest : test::CatalogueScene {
  explicit SceneUnderTest(const std::string& name)
      : CatalogueScene(name), masks(test::llvmpipe_renderer().render(prepared, "shadowmap").masks), control(masks.at(0)) {
    renderer::RenderOptions o;
    o.declare_light_matrices = true;
    const renderer::RenderResult declared = test::llvmpipe_renderer().render(prepared, "shadowmap", o);
    // The same drawing: declaring the matrices changes what is said, not what is drawn.
    for (std::size_t i = 0; i < masks.size(); ++i)
      if (declared.masks.at(i).pixels != masks[i].pixels) ADD_FAILURE() << "declaring the matrices changed mask " << i;
    nlohmann::json keys = nlohmann::json::parse(outputs::declaration_text(declared.declaration));
    keys.erase("technique");
    our_matrices = keys.dump();
    our_matrices = our_matrices.substr(1, our_matrices.size() - 2);  // the keys, without the braces
  }
  std::vector<Image8> masks;  // our render's, one per light
  Image8 control;             // light 0's (the single-light scenes' one mask)
  std::string our_matrices;   // our render's declaration with its light matrices, kOurMatrices
  conform::Judge judge;

  // Judges `mask` as light `light`'s, beside our render's masks of the other lights, declared with
  // `keys` (kOurMatrices: our_matrices), in folder `name`, as `technique`.
  conform::CaseJudgement judged(const std::string& name, const Image8& mask, const std::string& keys, std::size_t light = 0,
                                const std::string& technique = "shadowmap") {
    const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / scene.name / name;
    fs::remove_all(dir);  // no mask of an earlier run's layout left beside these
    fs::create_directories(dir);
    for (std::size_t i = 0; i < masks.size(); ++i)
      outputs::write_png(i == light ? mask : masks[i], dir / outputs::mask_name(i, masks.size()));
    const std::string& said = keys == kOurMatrices ? our_matrices : keys;
    std::ofstream(dir / "candidate.json") << "{\"technique\": \"" << technique << "\"" << (said.empty() ? "" : ", ") << said << "}\n";
    return judge.judge(&prepared, {reference, dir, "", false, {}});
  }
  // A mutant's name, with the light it mutates where the scene has several ("shifted-1px@light2").
  std::string mutant_name(const char* mutant, std::size_t light) const {
    return masks.size() == 1 ? std::string(mutant) : std::string(mutant) + "@light" + std::to_string(light);
  }
};

// Known limitations, each seen to fail in the predicted way (not FAIL, no unexplained core, and no
// more displaced pixels than the bound lets through), measured over the whole catalogue
// (docs/tolerance-model.md, "What is left"). Four kinds:
// - a declared map SMALLER than the one drawn, on the candidate's own views, widens the texel
//   footprint until it takes in the whole change: a 1-px shift of light_near_caster's shadow, the
//   shrunk shadows of nested_256_volumes' plates and a 1- or 2-px shift of alpha_cards' leaves (4
//   and 9 px left unexplained, each displaced, none in a core) are what such a map may honestly
//   show (a swapped tile on grazing_light's long edge is not: no texel grid gives its pixels
//   together, conform/zigzags.hpp, and it FAILs): nothing else is left unexplained, so
//   nothing is displaced either (the judge checks a declared size against the candidate's
//   staircases on the pack's grid only: conform/staircases.hpp);
// - camera_at_light, whose camera sits at the light: no cast shadow is visible, and a mutant changes
//   only slivers along silhouettes (1 to 4 px unexplained), as the engines' correct renders show
//   them (4 px, OpenSceneGraph SoftShadowMap);
// - a tile swapped where the declared footprint (a 512-texel own map, an 8-texel filter, all the
//   largest keys) takes in most of its change: what is left unexplained is a run along the boundary
//   (0 to 13 px in one 9 x 9 window; skinned_offscreen's third place 11 and 0), as thin as the runs
//   correct renders leave (up to 12), so the local-glitch bound (thresholds.hpp, kLocalGlitch)
//   cannot tell it from them either. The footprint at each such tile (2026-11-29, the cause model's
//   texel cells over the tile's 16 x 8 px): grazing_light's busiest place, an 8-texel box over the
//   auto map's 1.2-px texels reaching past the receiver's far edge (the zigzag check's samples
//   within that reach see a corner of the box's shadow, so it leaves the tile alone); a random tap
//   of the largest keys (the zigzag check is for fixed kernels); sun_horizon's third place, on the far ground,
//   17 px a texel at the auto size and 52 at 512; directional_light's second, 2.6 px a texel and one
//   random tap up to 8 texels away; skinned_offscreen's third, texels 5 px wide, so the tile's 8 px
//   across a diagonal boundary (5.7 px along its normal) stay within one texel of it. Each of these
//   cases says it is blind to 8x8 tiles: the resolving power swaps a tile at the same three places;
// - sun_horizon under all the largest keys at once (a 512-texel own map, whose texels are a metre
//   wide over 600 m of ground): a 1-px shift leaves 23 px unexplained, every one displaced, just
//   below that bound (0.92 % of the edges; correct renders reach 0.78 %).
// Any other mutant that does not FAIL fails the test, and so does a listed one that FAILs (the list
// must then shrink).
struct KnownGap {
  const char* scene;
  const char* mutant;
  const char* declarations;  // comma-separated grid names
};
constexpr KnownGap kKnownGaps[] = {
    {"grazing_light", "swapped-tile", "filter-8,largest"},
    {"light_near_caster", "shifted-1px", "largest"},
    {"nested_256_volumes", "shrunk-1px", "map-512,largest"},
    {"nested_256_volumes", "shrunk-2px", "map-512,largest"},
    {"camera_at_light", "shifted-1px", "map-512,largest"},
    {"camera_at_light", "shifted-2px", "largest"},
    {"camera_at_light", "swapped-tile",
     "ours,declared,slope-0,slope-0-own,slope-8,constant-6.4cm,constant-1m,normal-offset-4-texels,depth-bias-1%,distance-bias-1m,"
     "filter-8,map-512,map-512-pack,largest"},
    {"camera_at_light", "swapped-tile-2nd",
     "ours,declared,slope-0,slope-0-own,slope-8,constant-6.4cm,constant-1m,normal-offset-4-texels,depth-bias-1%,distance-bias-1m,"
     "filter-8,map-512,map-512-pack,largest"},
    {"sun_horizon", "shifted-1px", "largest"},
    {"directional_light", "swapped-tile-2nd", "largest"},
    {"sun_horizon", "swapped-tile-3rd", "filter-8,map-512,largest"},
    {"alpha_cards", "shifted-1px", "map-512,largest"},
    {"alpha_cards", "shifted-2px", "largest"},
    {"skinned_offscreen", "swapped-tile-3rd", "map-512,largest"},
};

// The resolving power's probe of a mutant's kind (resolving_power.hpp); none for the all-* masks.
std::optional<conform::ProbeKind> probe_kind_of(const std::string& mutant) {
  if (mutant == "shifted-1px") return conform::ProbeKind::Shift1;
  if (mutant == "shifted-2px") return conform::ProbeKind::Shift2;
  if (mutant == "grown-1px") return conform::ProbeKind::Grown1;
  if (mutant == "shrunk-1px" || mutant == "shrunk-2px") return conform::ProbeKind::Shrunk1;
  if (mutant.rfind("swapped-tile", 0) == 0) return conform::ProbeKind::Tile8;  // the probe tries the three places too
  return std::nullopt;
}

bool known_gap(const std::string& scene, const std::string& mutant, const std::string& declaration) {
  for (const KnownGap& g : kKnownGaps)
    if (scene == g.scene && mutant == g.mutant && ("," + std::string(g.declarations) + ",").find("," + declaration + ",") != std::string::npos)
      return true;
  return false;
}

class DeclarationGrid : public ::testing::TestWithParam<const char*> {};

TEST_P(DeclarationGrid, TheControlPassesAndNoDeclarationLetsAMutantPass) {
  SceneUnderTest s(GetParam());
  const conform::CaseJudgement control = s.judged("control", s.control, grid().front().json);
  ASSERT_EQ(control.comparison.decision.verdict, compare::Verdict::Pass) << "the control (our render, honestly declared)";
  // Under our own honest declaration a case resolves 1-px shifts, but where no cast shadow is in
  // view (then no shift changes a decided pixel).
  ASSERT_TRUE(control.resolving_power);
  const conform::ResolvingPower& power = *control.resolving_power;
  EXPECT_FALSE(power.blind_to(conform::ProbeKind::Shift1)) << power.summary();
  EXPECT_EQ(power.sees_nothing_of(conform::ProbeKind::Shift1), s.scene.name == "camera_at_light") << power.summary();
  // And so under the exact light matrices it was drawn with.
  const conform::CaseJudgement declared = s.judged("control-declared", s.control, kOurMatrices);
  EXPECT_EQ(declared.comparison.decision.verdict, compare::Verdict::Pass) << "the control, its light matrices declared";
  ASSERT_TRUE(declared.resolving_power);
  EXPECT_FALSE(declared.resolving_power->blind_to(conform::ProbeKind::Shift1)) << declared.resolving_power->summary();
  // The reference's decided pixels (255): a mutant is judged where it changes one of them. In a
  // scene of several lights, each light's mask is mutated in turn, the others kept as drawn.
  for (std::size_t light = 0; light < s.masks.size(); ++light) {
    const Image8 decided = outputs::read_image8(s.reference / outputs::decided_name(light, s.masks.size()), 1);
    for (const Mutant& m : mutants()) {
      Image8 mask = s.masks[light];
      m.mutate(mask);
      bool changes_decided = false;
      for (std::size_t i = 0; i < mask.pixels.size(); ++i)
        changes_decided = changes_decided || (decided.pixels[i] == 255 && mask.pixels[i] != s.masks[light].pixels[i]);
      if (!changes_decided) continue;  // changes no decided pixel of this scene: nothing to judge
      const std::string name = s.mutant_name(m.name, light);
      for (const Declaration& d : grid()) {
        const conform::CaseJudgement j = s.judged(name + "-" + d.name, mask, d.json, light);
        const compare::MaskMetrics& t = j.comparison.total;
        // The tiles' densest windows, the local-glitch bound's margin from below (thresholds.hpp).
        if (std::string(m.name).rfind("swapped-tile", 0) == 0)
          std::printf("%s %s declared %s: %s, %zu px unexplained, densest 9 x 9 window %zu\n", s.scene.name.c_str(), name.c_str(),
                      d.name.c_str(), compare::to_string(j.comparison.decision.verdict), t.unexplained, t.densest_unexplained);
        // The held-out tile answers to the resolving power, not to the list below: the blatant
        // mutants must FAIL, while a tile placed anywhere is one a declaration may explain, so long
        // as the case says so. It counts where the local-glitch bound can see it (densest_change).
        if (std::string(m.name) == "swapped-tile-held-out") {
          if (j.comparison.decision.verdict == compare::Verdict::Fail ||
              conform::densest_change(s.masks[light], mask, decided) <= compare::kLocalGlitch.densest_fail)
            continue;
          ASSERT_TRUE(j.resolving_power);
          EXPECT_TRUE(j.resolving_power->blind_to(conform::ProbeKind::Tile8) || j.resolving_power->sees_nothing_of(conform::ProbeKind::Tile8))
              << name << " declared " << d.name << " passes, but the case says: " << j.resolving_power->summary();
          continue;
        }
        if (known_gap(s.scene.name, name, d.name)) {
          EXPECT_NE(j.comparison.decision.verdict, compare::Verdict::Fail)
              << name << " declared " << d.name << " FAILs now: remove it from kKnownGaps";
          // Never silently: the case says it is blind to the kind of error it lets through.
          ASSERT_TRUE(j.resolving_power);
          if (const std::optional<conform::ProbeKind> kind = probe_kind_of(m.name)) {
            EXPECT_TRUE(j.resolving_power->blind_to(*kind) || j.resolving_power->sees_nothing_of(*kind))
                << name << " declared " << d.name << " passes, but the case says: " << j.resolving_power->summary();
          }
          EXPECT_EQ(t.unexplained_core, 0u) << name << " declared " << d.name << ": not the predicted kind of gap";
          EXPECT_LE(t.displaced, compare::kDisplaced.displaced_fail * static_cast<double>(t.edge_pixels))
              << name << " declared " << d.name << ": not the predicted kind of gap";
          continue;
        }
        EXPECT_EQ(j.comparison.decision.verdict, compare::Verdict::Fail)
            << name << " declared " << d.name << ": " << compare::to_string(j.comparison.decision.verdict) << " with "
            << t.unexplained << " px unexplained of " << t.wrong << " wrong (" << 100 * t.unexplained_ratio() << " % of "
            << t.edge_pixels << " edge px, core " << t.unexplained_core << ", " << t.displaced << " displaced, densest 9 x 9 window "
            << t.densest_unexplained << ")";
      }
    }
  }
}

TEST_P(DeclarationGrid, DeclaringLessNeverExplainsMore) {
  SceneUnderTest s(GetParam());
  std::vector<Mutant> masks = mutants();
  masks.insert(masks.begin(), Mutant{"control", [](Image8&) {}});
  for (std::size_t light = 0; light < s.masks.size(); ++light)
    for (const Mutant& m : masks) {
      if (light > 0 && std::string(m.name) == "control") continue;  // one control: every light as drawn
      Image8 mask = s.masks[light];
      m.mutate(mask);
      const std::string name = s.mutant_name(m.name, light);
      for (const std::vector<Declaration>& chain : chains()) {
        std::size_t before_unexplained = 0;
        compare::Verdict before = compare::Verdict::Pass;
        for (std::size_t i = 0; i < chain.size(); ++i) {
          const conform::CaseJudgement j = s.judged(name + "-chain-" + std::to_string(i), mask, chain[i].json, light);
          if (i > 0) {
            EXPECT_GE(j.comparison.total.unexplained, before_unexplained)
                << name << ": declaring " << chain[i].name << " instead of " << chain[i - 1].name << " explained more";
            EXPECT_GE(j.comparison.decision.verdict, before)
                << name << ": declaring " << chain[i].name << " instead of " << chain[i - 1].name << " improved the verdict";
          }
          before_unexplained = j.comparison.total.unexplained;
          before = j.comparison.decision.verdict;
        }
      }
    }
}

// A declared map size on the pack's grid is checked against the mask's own staircases
// (conform/staircases.hpp). Under grazing_light's sun 8 degrees up a 512-texel map's texel spans
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
// (conform/zigzags.hpp). The tile FAILs, and the pixels counted as zigzags all lie in it. Beside it,
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

// Peter-panning of a measured size, declared honestly: our shadowmap with a constant offset of
// 6.4 cm and of 26 cm along the sun (renderer/faults.hpp, constant_offset_world; the renderer
// declares it as candidate.json's constant_bias) leaves a lit line along the slab's contact that no
// correct map's bias explains: FAIL, beside the unfaulted render (PASS).
TEST(PeterPanning, AConstantBiasDeclaredHonestlyStillFailsOnItsLeak) {
  const test::CatalogueScene contact("contact_shadow");
  const scene::Scene& scene = contact.scene;
  const scene::PreparedScene& prepared = contact.prepared;
  const fs::path& reference = contact.reference;
  conform::Judge judge{false};  // verdicts only: no resolving power
  for (const double metres : {0.0, 0.064, 0.26}) {
    renderer::RenderOptions options;
    options.faults.shadow_map.constant_offset_world = metres;
    const renderer::RenderResult r = test::llvmpipe_renderer().render(prepared, "shadowmap", options);
    EXPECT_EQ(r.declaration.constant_bias, metres);
    const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / "peter-panning" / std::to_string(metres);
    renderer::write_outputs(r, test::llvmpipe_renderer().info(), scene, dir);
    const conform::CaseJudgement j = judge.judge(&prepared, {reference, dir, "shadowmap", false, {}});
    const compare::MaskMetrics& m = j.comparison.total;
    std::printf("contact_shadow, constant bias %.3f m declared: %s, %zu px false light, %zu explained by bias, %zu unexplained "
                "(%.2f %% of %zu edge px, core %zu)\n", metres, compare::to_string(j.comparison.decision.verdict), m.false_light,
                m.explained_bias, m.unexplained, 100 * m.unexplained_ratio(), m.edge_pixels, m.unexplained_core);
    EXPECT_EQ(j.comparison.decision.verdict, metres == 0 ? compare::Verdict::Pass : compare::Verdict::Fail)
        << metres << " m declared: " << m.false_light << " px false light, " << m.explained_bias << " explained by bias, "
        << m.unexplained << " unexplained (" << 100 * m.unexplained_ratio() << " % of " << m.edge_pixels << " edge px)";
  }
}

// The leak a correct map shows, explained: at 1024² with 512- and 1024-texel maps of grazing_light,
// one texel spans many pixels along the ground, and behind each box's far base our maps (front faces
// culled) store the box's bottom face or the ground, drawn two-sided, both with the ground's steep
// slope offset; the ground there comes out lit for about two texels (a wedge at each box's base).
// The cause model stores what such a map stores (reference/causes.cpp, texel_gives), so the leak is
// explained by the bias: no FAIL, no unexplained core. Before it did, 1024 texels FAILed shadowmap
// and csm with 248 px unexplained and a 4-px core.
TEST(ContactLeak, ACorrectMapsLeakBehindABoxOnAGrazingGroundIsExplained) {
  scene::Scene scene = scene::load_scene(conform::default_catalogue() / "grazing_light.json");
  scene.width *= 4;
  scene.height *= 4;
  conform::Judge judge{false};  // verdicts only: no resolving power
  for (const int size : {512, 1024}) {
    scene::PrepareOptions prepare;
    prepare.shadow_map_size = size;
    const scene::PreparedScene prepared = scene::prepare_scene(scene, kDefaultConvention, prepare);
    conform::ReferenceSettings settings;
    settings.key_executable = SHADOWREF_EXE;
    const fs::path reference = conform::ensure_reference(prepared, SHADOWREF_TEST_CACHE, settings).dir;
    for (const char* technique : {"shadowmap", "csm"}) {
      const renderer::RenderResult r = test::llvmpipe_renderer().render(prepared, technique);
      ASSERT_EQ(r.declaration.shadow_map_size, size);
      const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / "contact-leak" / (std::string(technique) + "-" + std::to_string(size));
      renderer::write_outputs(r, test::llvmpipe_renderer().info(), scene, dir);
      const conform::CaseJudgement j = judge.judge(&prepared, {reference, dir, technique, false, {}});
      const compare::MaskMetrics& m = j.comparison.total;
      std::printf("grazing_light at 1024², %s, %d texels: %s, %zu px false light, %zu explained by bias, %zu unexplained "
                  "(%.2f %% of %zu edge px, core %zu)\n", technique, size, compare::to_string(j.comparison.decision.verdict),
                  m.false_light, m.explained_bias, m.unexplained, 100 * m.unexplained_ratio(), m.edge_pixels,
                  m.unexplained_core);
      EXPECT_NE(j.comparison.decision.verdict, compare::Verdict::Fail) << technique << " at " << size << " texels";
      EXPECT_EQ(m.unexplained_core, 0u) << technique << " at " << size << " texels";
      EXPECT_GT(m.explained_bias, 0u) << technique << " at " << size << " texels: the leak is the bias's";
    }
  }
}

// A map that leaves open meshes out (OpenSceneGraph's ShadowMap culls every front face, the
// ground's too) is a correct map wherever no open mesh faces the light between a point and the
// light: under a wide filter it reads a receiver in front of a box as lit where a two-sided ground
// reads it shadowed. On sun_horizon the near box's face toward the light lies in the shadow of the
// tower behind the camera, a strip 2.4 texels wide in a 1024-texel map: a 5.6-texel kernel over a
// map without the ground lights it, and the judge explains each of those pixels (before it knew such
// maps, 132 of the 783 stayed unexplained: OpenSceneGraph's SoftShadowMap FAILed there). Beside it the loss such a map may not
// hide: single_sided_cards with its cards left out too (every pixel lit: nothing else casts) FAILs
// under the same declaration.
TEST(OpenMeshesCulled, AWideFilterOverAMapWithoutTheGroundIsExplainedButALostCardIsNot) {
  // OpenSceneGraph's SoftShadowMap as its harness declares it: a jittered kernel of 5.62 texels
  // over a 1024-texel map, no bias, and the matrices ShadowMap fitted to sun_horizon's whole bound
  // (an orthographic box 849 m wide, 850 m from the scene's centre toward the sun).
  outputs::CandidateDeclaration wide;
  wide.technique = "shadowmap-pcf";
  wide.filter_radius_texels = 5.62;
  wide.sampling = outputs::Sampling::Random;
  wide.slope_bias_texels = 0;
  wide.shadow_map_size = 1024;
  wide.light_views = outputs::LightViews::Declared;
  wide.views = {{.view = {0.127775315, -0.894427191, -0.428571428, 0, 0.958314846, 0, 0.285714291, 0, -0.255550631,
                          -0.447213595, 0.857142856, 0, -5.74988908, 0, -850.327284, 1},
                 .projection = {0.00235678696, 0, 0, 0, 0, 0.00235678696, 0, 0, 0, 0, -0.00235678705, 0, 0, 0, -2.00000004, 1}}};
  {
    const test::CatalogueScene sun("sun_horizon");
    const Image8 mask = outputs::read_image8(sun.reference / "mask.png", 1);
    const Image8 decided = outputs::read_image8(sun.reference / "decided.png", 1);
    reference::CauseModel model(sun.prepared);
    std::size_t on_face = 0, explained = 0;
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * mask.width + x);
        if (mask.pixels[i] != kMaskShadowed || !outputs::is_flag_set(decided.pixels[i])) continue;
        const std::optional<reference::CauseModel::TexelCell> cell = model.texel_cell(0, x, y, wide);
        // near_box_b: a unit cube at (2, 0.5, 0); its face toward the light is z = 0.5.
        if (!cell || std::abs(cell->p.z() - 0.5) > 1e-3 || std::abs(cell->p.x() - 2.0) > 0.5) continue;
        ++on_face;
        explained += model.explain(0, x, y, wide, true) == outputs::Cause::TexelFootprint;
      }
    std::printf("sun_horizon, the near box's face in the tower's shadow: %zu of %zu px explained lit under a 5.62-texel filter\n",
                explained, on_face);
    ASSERT_GT(on_face, 20u) << "the tower's shadow on the near box's face is in view";
    EXPECT_EQ(explained, on_face);
  }
  const test::CatalogueScene cards("single_sided_cards");
  Image8 lost = outputs::read_image8(cards.reference / "mask.png", 1);
  for_surface(lost, [](std::uint8_t& v) { v = kMaskLit; });
  const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / "open-meshes-culled" / "cards-lost";
  fs::create_directories(dir);
  outputs::write_png(lost, dir / "mask.png");
  std::ofstream(dir / "candidate.json") << R"({"technique": "shadowmap-pcf", "filter_radius_texels": 5.62, )"
                                        << R"("sampling": "random", "slope_bias_texels": 0, "shadow_map_size": 1024})" << "\n";
  const conform::CaseJudgement j = conform::Judge().judge(&cards.prepared, {cards.reference, dir, "", false, {}});
  const compare::MaskMetrics& m = j.comparison.total;
  std::printf("single_sided_cards with the cards left out: %s, %zu px unexplained, core %zu\n",
              compare::to_string(j.comparison.decision.verdict), m.unexplained, m.unexplained_core);
  EXPECT_EQ(j.comparison.decision.verdict, compare::Verdict::Fail);
  EXPECT_GT(m.unexplained_core, 0u) << "the cards' whole shadows are lost, not a boundary band";
}

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
  const auto tiles = [](const conform::ResolvingPower& r) {
    std::string s;
    for (const conform::Probe& p : r.probes)
      if (p.kind == conform::ProbeKind::Tile8) s += p.name + ": " + compare::to_string(p.verdict) + ", " + std::to_string(p.unexplained) + " unexplained\n";
    return s;
  };
  conform::Judge fresh;
  const conform::ResolvingPower alone = judged_as(fresh, "csm-pcf");
  conform::Judge shared;
  const conform::ResolvingPower map = judged_as(shared, "shadowmap-pcf");
  const conform::ResolvingPower after = judged_as(shared, "csm-pcf");
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

// Directional light over flat ground (acne's home), a sun 8 degrees up (grazing), a slab on the ground
// (contact shadows: peter-panning), a point light's cube over a sphere's whole shadow, a box whose
// one-pixel shift changes few decided pixels (cornell_box: below the unexplained bound under every
// declaration, caught as displaced), 600 m of ground under one map (sun_horizon: its control's own
// staircases beside every mutant), the camera at the light (camera_at_light: the known gaps of the
// second kind); and the content scenes: alpha-masked cards, a fence and vertex alpha, single-sided
// cards, a posed character and one outside the camera's view. CTest runs these thirteen;
// SHADOWREF_GRID_SCENES (comma-separated catalogue names) runs the grid on others by hand, e.g. the
// whole catalogue, as docs/tolerance-model.md records.
std::vector<const char*> grid_scenes() {
  // Filled once (gtest may ask again), and never grown after: the names' pointers stay valid.
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    const char* env = std::getenv("SHADOWREF_GRID_SCENES");
    const std::string list = env ? env : "";
    for (std::size_t start = 0; start < list.size();) {
      const std::size_t comma = std::min(list.find(',', start), list.size());
      if (comma > start) n.push_back(list.substr(start, comma - start));
      start = comma + 1;
    }
    return n;
  }();
  std::vector<const char*> out;
  for (const std::string& n : names) out.push_back(n.c_str());
  if (!out.empty()) return out;
  return {"directional_light", "grazing_light", "contact_shadow", "ground_sphere", "cornell_box", "sun_horizon",
          "camera_at_light", "alpha_cards", "alpha_fence", "alpha_vertex", "single_sided_cards", "skinned_character",
          "skinned_offscreen", "level_cut"};
}
INSTANTIATE_TEST_SUITE_P(Scenes, DeclarationGrid, ::testing::ValuesIn(grid_scenes()),
                         [](const ::testing::TestParamInfo<const char*>& i) { return std::string(i.param); });

}  // namespace
}  // namespace shadowref
