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
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "grid_scene.hpp"

namespace shadowref {
namespace {

using namespace test;  // the grid's scene and mutations (grid_scene.hpp)

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
      // Where no tile probe was put: the place farthest from the three (tolerance::tile_places), one
      // the resolving power's sweep alone speaks for.
      {"swapped-tile-held-out", swapped_tile(static_cast<int>(tolerance::kBusiestTilePlaces))},
  };
}

// A declaration: candidate.json's bias and footprint keys over the technique (shadowmap).
struct Declaration {
  std::string name;
  std::string json;  // the keys beyond "technique"
};


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


// Known limitations, each seen to fail in the predicted way (not FAIL, no unexplained core, and no
// more displaced pixels than the bound lets through), measured over the whole catalogue
// (docs/tolerance-model.md, "What is left"). Four kinds:
// - a declared map SMALLER than the one drawn, on the candidate's own views, widens the texel
//   footprint until it takes in the whole change: a 1-px shift of light_near_caster's shadow, the
//   shrunk shadows of nested_256_volumes' plates and a 1- or 2-px shift of alpha_cards' leaves (4
//   and 9 px left unexplained, each displaced, none in a core) are what such a map may honestly
//   show (a swapped tile on grazing_light's long edge is not: no texel grid gives its pixels
//   together, tolerance/zigzags.hpp, and it FAILs): nothing else is left unexplained, so
//   nothing is displaced either (the judge checks a declared size against the candidate's
//   staircases on the pack's grid only: tolerance/staircases.hpp);
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
std::optional<tolerance::ProbeKind> probe_kind_of(const std::string& mutant) {
  if (mutant == "shifted-1px") return tolerance::ProbeKind::Shift1;
  if (mutant == "shifted-2px") return tolerance::ProbeKind::Shift2;
  if (mutant == "grown-1px") return tolerance::ProbeKind::Grown1;
  if (mutant == "shrunk-1px" || mutant == "shrunk-2px") return tolerance::ProbeKind::Shrunk1;
  if (mutant.rfind("swapped-tile", 0) == 0) return tolerance::ProbeKind::Tile8;  // the probe tries the three places too
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
  const tolerance::ResolvingPower& power = *control.resolving_power;
  EXPECT_FALSE(power.blind_to(tolerance::ProbeKind::Shift1)) << power.summary();
  EXPECT_EQ(power.sees_nothing_of(tolerance::ProbeKind::Shift1), s.scene.name == "camera_at_light") << power.summary();
  // And so under the exact light matrices it was drawn with.
  const conform::CaseJudgement declared = s.judged("control-declared", s.control, kOurMatrices);
  EXPECT_EQ(declared.comparison.decision.verdict, compare::Verdict::Pass) << "the control, its light matrices declared";
  ASSERT_TRUE(declared.resolving_power);
  EXPECT_FALSE(declared.resolving_power->blind_to(tolerance::ProbeKind::Shift1)) << declared.resolving_power->summary();
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
              tolerance::densest_change(s.masks[light], mask, decided) <= compare::kLocalGlitch.densest_fail)
            continue;
          ASSERT_TRUE(j.resolving_power);
          EXPECT_TRUE(j.resolving_power->blind_to(tolerance::ProbeKind::Tile8) || j.resolving_power->sees_nothing_of(tolerance::ProbeKind::Tile8))
              << name << " declared " << d.name << " passes, but the case says: " << j.resolving_power->summary();
          continue;
        }
        if (known_gap(s.scene.name, name, d.name)) {
          EXPECT_NE(j.comparison.decision.verdict, compare::Verdict::Fail)
              << name << " declared " << d.name << " FAILs now: remove it from kKnownGaps";
          // Never silently: the case says it is blind to the kind of error it lets through.
          ASSERT_TRUE(j.resolving_power);
          if (const std::optional<tolerance::ProbeKind> kind = probe_kind_of(m.name)) {
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
