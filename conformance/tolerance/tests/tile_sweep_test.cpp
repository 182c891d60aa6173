// tile_sweep_test.cpp — the tile sweep's places are exactly those where a tile swapped alone does not
// FAIL one comparison of its own (compare_mask, decide) and shows something (densest_change): the
// sweep reads every place from two comparisons, the oracle compares every place apart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <vector>

#include "shadowref/compare/compare.hpp"
#include "shadowref/compare/thresholds.hpp"
#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/outputs/image.hpp"
#include "tile_sweep.hpp"

namespace shadowref::tolerance {
namespace {

using outputs::Image8;

constexpr int kW = 160, kH = 120;
constexpr int kStripes = 110;  // x from here: 2-px stripes, edges enough for a tile to pass the ratio bound
constexpr int kJudgedWidth = 100;  // the oracle's places lie left of this (a tile there sees no stripe)

// A shadowed disc and a shadowed wedge on a lit receiver, a strip and a box of no surface: straight,
// curved and diagonal boundaries, and coverage changes where a tile crosses a silhouette. Right of
// them, stripes: the edge pixels of a larger scene, against which a tile's unexplained count weighs.
Image8 scene_mask() {
  Image8 m{kW, kH, 1, std::vector<std::uint8_t>(kW * kH, outputs::kMaskLit)};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      std::uint8_t& v = m.pixels[static_cast<std::size_t>(y * kW + x)];
      if (std::hypot(x - 40.0, y - 60.0) < 22.5) v = outputs::kMaskShadowed;
      if (x > 70 && x < kStripes && y > 2 * (x - 70)) v = outputs::kMaskShadowed;
      if (x < 3 || (x >= 80 && x < kStripes && y < 10)) v = outputs::kMaskNoSurface;
      if (x >= kStripes && (x / 2) % 2 == 0) v = outputs::kMaskShadowed;
    }
  return m;
}

// Decided but for a pattern along the disc's rim (the reference's undecided pixels at a boundary).
Image8 scene_decided() {
  Image8 d{kW, kH, 1, std::vector<std::uint8_t>(kW * kH, outputs::kFlagSet)};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (std::abs(std::hypot(x - 40.0, y - 60.0) - 22.5) < 1.5 && (x + y) % 3 == 0)
        d.pixels[static_cast<std::size_t>(y * kW + x)] = outputs::kFlagClear;
  return d;
}

// A cause per pixel and answer, as the cause model's is (never of the pixels around it): near the
// disc's rim, most answers are within a texel of it.
const compare::Explainer kExplainer = [](std::size_t, int x, int y, bool lit) {
  const double rim = std::abs(std::hypot(x - 40.0, y - 60.0) - 22.5);
  if (rim < 4.0 && (5 * x + 3 * y + (lit ? 1 : 0)) % 4 != 0) return compare::Cause::TexelFootprint;
  return compare::Cause::Unexplained;
};

struct Oracle {
  std::vector<std::pair<int, int>> places;  // not FAILing and showing something
  std::size_t failing = 0;                  // showing something and FAILing
};

Oracle every_place_alone(const Image8& mask, const Image8& decided, const compare::Threshold& t, const compare::CompareOptions& o) {
  Oracle out;
  for (int y = 0; y + 8 <= mask.height; ++y)
    for (int x = 0; x + 16 <= kJudgedWidth; ++x) {
      const Image8 tile = swapped_tile_at(mask, {x, y});
      if (densest_change(mask, tile, decided) <= compare::kLocalGlitch.densest_fail) continue;
      const compare::MaskComparison c = compare::compare_mask(mask, decided, tile, "tile", 0, o);
      if (compare::decide(c.metrics, t).verdict == compare::Verdict::Fail)
        ++out.failing;
      else
        out.places.emplace_back(x, y);
    }
  return out;
}

std::vector<std::pair<int, int>> swept(const Image8& mask, const Image8& decided, const compare::Threshold& t, const compare::CompareOptions& o) {
  std::vector<std::pair<int, int>> out;
  for (const TilePlace& p : tiles_not_failing(mask, decided, 0, t, o))
    if (p.x + 16 <= kJudgedWidth) out.emplace_back(p.x, p.y);
  return out;
}

compare::CompareOptions quick(const compare::Explainer* explain, bool invariant) {
  compare::CompareOptions o;
  o.explain = explain;
  o.no_cast_shadow_invariant = invariant;
  o.displacement_up_to = -1;
  o.error_image = false;
  return o;
}

TEST(TileSweep, FindsExactlyThePlacesWhereATileAloneDoesNotFail) {
  const Image8 mask = scene_mask(), decided = scene_decided();
  struct Variant {
    const char* name;
    const compare::Threshold* threshold;
    const compare::Explainer* explain;
    bool invariant;
  };
  for (const Variant& v : {Variant{"shadow map, explained", &compare::kShadowMap, &kExplainer, false},
                           Variant{"shadow map, the scene's invariant", &compare::kShadowMap, &kExplainer, true},
                           Variant{"exact geometry, nothing explained", &compare::kExactGeometry, nullptr, false}}) {
    const compare::CompareOptions o = quick(v.explain, v.invariant);
    const Oracle oracle = every_place_alone(mask, decided, *v.threshold, o);
    EXPECT_EQ(swept(mask, decided, *v.threshold, o), oracle.places) << v.name;
    std::printf("%s: %zu places pass alone, %zu FAIL\n", v.name, oracle.places.size(), oracle.failing);
    // Both sides occur, so that the equality tells places apart.
    EXPECT_GT(oracle.failing, 0u) << v.name;
    if (v.explain) {
      EXPECT_FALSE(oracle.places.empty()) << v.name << ": no tile passes; the explainer proves nothing";
    }
  }
}

TEST(TileSweep, AnImageTooSmallForATileHasNoPlace) {
  const Image8 mask{15, 8, 1, std::vector<std::uint8_t>(15 * 8, outputs::kMaskLit)};
  const Image8 decided{15, 8, 1, std::vector<std::uint8_t>(15 * 8, outputs::kFlagSet)};
  EXPECT_TRUE(tiles_not_failing(mask, decided, 0, compare::kShadowMap, quick(nullptr, false)).empty());
}

}  // namespace
}  // namespace shadowref::tolerance
