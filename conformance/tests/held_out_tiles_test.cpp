// held_out_tiles_test.cpp — a case's resolving power holds for tiles on a render, not only on the
// reference it probes: on every default scene, our own correct shadow-map render is judged under its
// own declaration (the one `shadowref conform` judges it with), then with an 8 × 8 tile swapped at
// each of the places farthest from the tile probes' (tolerance::tile_places after its
// kBusiestTilePlaces; on a boundary too short for them, the probes' places moved by half a tile).
// The probes and the sweep swap tiles on the reference's masks; these swap them on the render's,
// whose own explained errors lie beside them. A held-out tile the local-glitch bound can see (more
// than 18 decided pixels in one 9 x 9 window, tolerance::densest_change) may PASS only in a case that
// says it is blind to 8x8 tiles (or that no tile shows anything): a PASS beside "resolves … 8x8 tiles
// at every place" claims more than the probes saw. The control (the render itself) must PASS, so
// that each tile's verdict is the tile's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "catalogue_scene.hpp"
#include "llvmpipe_renderer.hpp"
#include "shadowref/compare/thresholds.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;
using outputs::Image8;

constexpr std::size_t kHeldOut = 3;  // tiles per light, beyond the probes' places

// Writes `masks` with light `light`'s replaced by `mask`, and `declaration`, into `dir`.
void write_candidate(const fs::path& dir, const std::vector<Image8>& masks, const Image8* mask, std::size_t light,
                     const std::string& declaration) {
  fs::remove_all(dir);  // no mask of an earlier run's layout left beside these
  fs::create_directories(dir);
  for (std::size_t i = 0; i < masks.size(); ++i)
    outputs::write_png(mask && i == light ? *mask : masks[i], dir / outputs::mask_name(i, masks.size()));
  std::ofstream(dir / "candidate.json") << declaration << "\n";
}

class HeldOutTiles : public ::testing::TestWithParam<std::string> {};

TEST_P(HeldOutTiles, APassBesideResolvedTilesIsOneTheProbesCouldHaveSeen) {
  test::CatalogueScene s(GetParam());
  const renderer::RenderResult ours = test::llvmpipe_renderer().render(s.prepared, "shadowmap");
  const std::string declaration = outputs::declaration_text(ours.declaration);
  const fs::path root = fs::path(SHADOWREF_TEST_OUT) / s.scene.name;
  conform::Judge judge;  // one judge: the probes are computed once, for the control
  write_candidate(root / "control", ours.masks, nullptr, 0, declaration);
  const conform::CaseJudgement control = judge.judge(&s.prepared, {s.reference, root / "control", "", true, {}});
  ASSERT_EQ(control.comparison.decision.verdict, compare::Verdict::Pass) << "the control: our render, as conform judges it";
  ASSERT_TRUE(control.resolving_power);
  const tolerance::ResolvingPower& power = *control.resolving_power;
  const bool says_blind = power.blind_to(tolerance::ProbeKind::Tile8) || power.sees_nothing_of(tolerance::ProbeKind::Tile8);
  std::printf("%s: %s\n", s.scene.name.c_str(), power.summary().c_str());
  std::size_t judged = 0;
  for (std::size_t light = 0; light < ours.masks.size(); ++light) {
    const std::size_t lights = ours.masks.size();
    // The places the probes did not use: those of the reference's mask, which the probes swap.
    const Image8 reference = outputs::read_image8(s.reference / outputs::mask_name(light, lights), 1);
    const Image8 decided = outputs::read_image8(s.reference / outputs::decided_name(light, lights), 1);
    std::vector<tolerance::TilePlace> places = tolerance::tile_places(reference, tolerance::kBusiestTilePlaces + kHeldOut);
    const std::size_t probed = std::min(places.size(), tolerance::kBusiestTilePlaces);
    // Where the lattice of places ends before the held-out ones (a short boundary), the places
    // between the probes': each probed place moved by half a tile, overlapping it and not probed.
    if (places.size() == probed) {
      for (std::size_t k = 0; k < probed && k < kHeldOut; ++k) {
        if (places[k].x + 20 <= reference.width && places[k].y + 12 <= reference.height) places.push_back({places[k].x + 4, places[k].y + 4});
      }
    }
    for (std::size_t k = probed; k < places.size(); ++k) {
      const Image8 tile = tolerance::swapped_tile_at(ours.masks[light], places[k]);
      // What the local-glitch bound can see of it (resolving_power.hpp): its densest 9 x 9 window.
      const std::size_t densest = tolerance::densest_change(ours.masks[light], tile, decided);
      const std::string name = "held-out-" + std::to_string(light) + "-" + std::to_string(k);
      write_candidate(root / name, ours.masks, &tile, light, declaration);
      const conform::CaseJudgement j = judge.judge(&s.prepared, {s.reference, root / name, "", true, {}});
      const compare::Verdict v = j.comparison.decision.verdict;
      std::printf("  light %zu, held-out place %zu (%d, %d): %zu decided px in its densest 9 x 9 window, %s, %zu unexplained\n", light,
                  k + 1, places[k].x, places[k].y, densest, compare::to_string(v), j.comparison.total.unexplained);
      // A tile within the local-glitch bound is one no verdict promises to see (resolving_power.hpp).
      if (densest <= compare::kLocalGlitch.densest_fail) continue;
      ++judged;
      if (v == compare::Verdict::Fail) continue;
      EXPECT_TRUE(says_blind) << "light " << light << ": a tile at (" << places[k].x << ", " << places[k].y << ") with " << densest
                              << " decided px in one 9 x 9 window is " << compare::to_string(v) << " while the case says: " << power.summary();
    }
  }
  // Where every held-out tile is within the bound (a short or gentle boundary), there is nothing to
  // hold the statement to on this scene; it is said, and the other scenes hold it.
  if (judged == 0) std::printf("  no held-out tile beyond the local-glitch bound\n");
}

std::vector<std::string> default_scenes() {
  std::vector<std::string> names;
  for (const fs::path& p : conform::select_scenes(conform::default_catalogue(), {})) names.push_back(p.stem().string());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Scenes, HeldOutTiles, ::testing::ValuesIn(default_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

}  // namespace
}  // namespace shadowref
