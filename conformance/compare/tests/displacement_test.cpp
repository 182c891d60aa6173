// displacement_test.cpp — displaced shadows (displacement.hpp) on synthetic masks: a disc's shadow
// moved or grown in screen space is found, with its move, and FAILs past the bound even where a
// generous explainer takes most of its pixels; a staircase that leans both ways is not displaced,
// and explaining less never improves the verdict.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "shadowref/compare/compare.hpp"

namespace shadowref::compare {
namespace {

constexpr int kSize = 96;

// A lit ground with a disc of shadow of radius 20 at (48 + dx, 48) and three shadowed stripes the
// whole width (rows 80, 86, 92: long boundaries that a horizontal move leaves as they are), all
// grown by `grow` px (a square).
Image8 scene(int dx, int grow = 0) {
  Image8 m{kSize, kSize, 1, std::vector<std::uint8_t>(kSize * kSize, outputs::kMaskLit)};
  const auto shadowed = [dx](int x, int y) {
    return std::hypot(x + 0.5 - 48 - dx, y + 0.5 - 48) < 20.0 || y == 80 || y == 86 || y == 92;
  };
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int v = -grow; v <= grow; ++v)
        for (int u = -grow; u <= grow; ++u)
          if (shadowed(x + u, y + v)) m.pixels[static_cast<std::size_t>(y * kSize + x)] = outputs::kMaskShadowed;
  return m;
}

const Image8 kDecided{kSize, kSize, 1, std::vector<std::uint8_t>(kSize * kSize, 255)};

// As compare_folders compares: the displaced count looked for up to as many unexplained pixels as
// edge pixels.
MaskComparison compared(const Image8& ref, const Image8& cand, const Explainer* explain) {
  CompareOptions o;
  o.explain = explain;
  o.displacement_up_to = 1.0;
  return compare_mask(ref, kDecided, cand, "mask", 0, o);
}

// Explains every wrong pixel left of x = 65 and on the stripes, as a coarse map's footprint would
// most of them, leaving the disc's right rim unexplained: about 2 % of the edge pixels, below the
// unexplained bound.
const Explainer kMostly = [](std::size_t, int x, int y, bool) {
  return x < 65 || y >= 70 ? Cause::TexelFootprint : Cause::Unexplained;
};
const Explainer kAll = [](std::size_t, int, int, bool) { return Cause::TexelFootprint; };

TEST(Displacement, AShadowMovedOnePixelIsFoundAndFailsWhereTheFootprintTakesMostOfIt) {
  const Image8 ref = scene(0);
  const MaskComparison c = compared(ref, scene(1), &kMostly);
  ASSERT_GT(c.metrics.unexplained, 0u);
  EXPECT_LE(c.metrics.unexplained_ratio(), kShadowMap.unexplained_fail) << "below the unexplained bound on its own";
  EXPECT_EQ(c.metrics.displaced, c.metrics.unexplained) << "every unexplained pixel comes right moved back";
  EXPECT_EQ(c.displacement.move.dx, 1);
  EXPECT_EQ(c.displacement.move.dy, 0);
  EXPECT_EQ(describe(c.displacement.move), "shadows moved 1 px right");
  EXPECT_LT(c.displacement.wrong_after, c.displacement.wrong_before);
  const Decision j = decide(c.metrics, kShadowMap, describe(c.displacement.move));
  EXPECT_EQ(j.verdict, Verdict::Fail);
  ASSERT_FALSE(j.reasons.empty());
  EXPECT_NE(j.reasons.back().find("displaced shadows"), std::string::npos) << j.reasons.back();
  EXPECT_NE(j.reasons.back().find("moved 1 px right"), std::string::npos) << j.reasons.back();
  // The same disc unmoved: nothing wrong, nothing displaced (the control).
  const MaskComparison same = compared(ref, ref, &kMostly);
  EXPECT_EQ(same.metrics.displaced, 0u);
  EXPECT_EQ(decide(same.metrics, kShadowMap).verdict, Verdict::Pass);
}

TEST(Displacement, AGrownShadowIsShrunkBack) {
  // A growth changes the whole rim: the footprint takes all but its right end.
  const Explainer more = [](std::size_t, int x, int y, bool) {
    return x < 66 || y >= 70 ? Cause::TexelFootprint : Cause::Unexplained;
  };
  const MaskComparison c = compared(scene(0), scene(0, 1), &more);
  EXPECT_LE(c.metrics.unexplained_ratio(), kShadowMap.unexplained_fail);
  EXPECT_GT(c.metrics.displaced, 0u);
  EXPECT_EQ(c.displacement.move.grow, 1);
  EXPECT_EQ(describe(c.displacement.move), "shadows grown by 1 px");
  EXPECT_EQ(c.displacement.wrong_after, 0u);
}

TEST(Displacement, AStaircaseThatLeansBothWaysIsNotDisplaced) {
  // Rows of the disc moved alternately 1 px right and 1 px left, as a coarse map's staircases fall
  // on both sides of a boundary: no move lowers the shadow errors, so none is displaced.
  const Image8 ref = scene(0);
  const Image8 right = scene(1), left = scene(-1);
  Image8 cand = ref;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * kSize + x);
      cand.pixels[i] = (y / 2) % 2 ? right.pixels[i] : left.pixels[i];
    }
  const MaskComparison c = compared(ref, cand, &kMostly);
  ASSERT_GT(c.metrics.unexplained, 0u);
  EXPECT_EQ(c.metrics.displaced, 0u) << describe(c.displacement.move);
}

TEST(Displacement, ExplainingLessNeverImprovesTheVerdict) {
  // Verdicts along ever smaller explanations: PASS (all explained), FAIL (displaced), FAIL (beyond
  // the unexplained bound, and displaced).
  const Image8 ref = scene(0), cand = scene(1);
  const MaskComparison all = compared(ref, cand, &kAll), most = compared(ref, cand, &kMostly);
  EXPECT_EQ(all.metrics.displaced, 0u) << "nothing unexplained, nothing displaced";
  EXPECT_EQ(decide(all.metrics, kShadowMap).verdict, Verdict::Pass);
  EXPECT_GT(most.metrics.displaced, 0u);
  EXPECT_EQ(decide(most.metrics, kShadowMap).verdict, Verdict::Fail);
  const MaskComparison none = compared(ref, cand, nullptr);
  EXPECT_GT(none.metrics.unexplained_ratio(), kShadowMap.unexplained_fail);
  EXPECT_GE(none.metrics.displaced, most.metrics.displaced);
  EXPECT_EQ(decide(none.metrics, kShadowMap).verdict, Verdict::Fail);
}

// The plain definition, every move on the whole image (displacement.cpp judges each move on the
// band near boundaries only): the same move, count and errors on random masks.
TEST(Displacement, TheBandEqualsThePlainDefinition) {
  std::mt19937 rng(7);
  int found = 0;  // rounds with a displacement: the comparison is not of zeros
  for (int round = 0; round < 40; ++round) {
    const int w = 24 + round % 7, h = 20 + round % 5;
    const auto random_mask = [&](int density) {
      Image8 m{w, h, 1, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h), outputs::kMaskLit)};
      // Blobs: a few discs of shadow and a little background, so that boundaries are runs.
      for (int b = 0; b < 3; ++b) {
        const int cx = static_cast<int>(rng() % static_cast<unsigned>(w)), cy = static_cast<int>(rng() % static_cast<unsigned>(h));
        const int r = 2 + static_cast<int>(rng() % 5);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < r * r) m.pixels[static_cast<std::size_t>(y * w + x)] = 0;
      }
      for (std::uint8_t& v : m.pixels)
        if (static_cast<int>(rng() % 100) < density) v = rng() % 4 == 0 ? outputs::kMaskNoSurface : (v ? 0 : 255);
      return m;
    };
    const Image8 ref = random_mask(0), cand = random_mask(3);
    Image8 dec{w, h, 1, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h), 255)};
    for (std::uint8_t& v : dec.pixels)
      if (rng() % 8 == 0) v = 0;
    const bool invariant = round % 2 == 1;
    const auto cls = [](std::uint8_t v) { return v < 64 ? 0 : (v < 192 ? 1 : 2); };
    std::vector<std::size_t> unexplained;
    for (std::size_t i = 0; i < ref.pixels.size(); ++i)
      if (cls(ref.pixels[i]) != 1 && cls(cand.pixels[i]) != 1 && cls(ref.pixels[i]) != cls(cand.pixels[i]) && rng() % 3)
        unexplained.push_back(i);
    // The plain definition.
    const auto undone = [&](const ShadowMove& m) {
      std::vector<int> out(cand.pixels.size());
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const std::size_t i = static_cast<std::size_t>(y * w + x);
          int c = cls(cand.pixels[i]);
          if (c != 1 && m.grow == 0) {
            const int u = x + m.dx, v = y + m.dy;
            if (u >= 0 && v >= 0 && u < w && v < h && cls(cand.pixels[static_cast<std::size_t>(v * w + u)]) != 1)
              c = cls(cand.pixels[static_cast<std::size_t>(v * w + u)]);
          } else if (c != 1) {
            const int into = m.grow > 0 ? 2 : 0;
            for (int v = y - std::abs(m.grow); v <= y + std::abs(m.grow); ++v)
              for (int u = x - std::abs(m.grow); u <= x + std::abs(m.grow); ++u)
                if (u >= 0 && v >= 0 && u < w && v < h && cls(cand.pixels[static_cast<std::size_t>(v * w + u)]) == into) c = into;
          }
          out[i] = c;
        }
      return out;
    };
    const auto errors = [&](const std::vector<int>& c) {
      std::size_t n = 0;
      for (std::size_t i = 0; i < c.size(); ++i) {
        const int r = cls(ref.pixels[i]);
        if (r == 1 || c[i] == 1 || r == c[i]) continue;
        n += dec.pixels[i] >= 128 || (invariant && r == 2 && c[i] == 0);
      }
      return n;
    };
    std::vector<int> as_is(cand.pixels.size());
    for (std::size_t i = 0; i < as_is.size(); ++i) as_is[i] = cls(cand.pixels[i]);
    Displacement plain;
    plain.wrong_before = plain.wrong_after = errors(as_is);
    std::vector<ShadowMove> moves;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        if (dx != 0 || dy != 0) moves.push_back({dx, dy, 0});
    for (const int g : {1, 2, -1, -2}) moves.push_back({0, 0, g});
    for (const ShadowMove& m : moves) {
      const std::vector<int> moved = undone(m);
      std::size_t fixed = 0;
      for (const std::size_t i : unexplained) fixed += moved[i] == cls(ref.pixels[i]);
      const std::size_t after = errors(moved);
      if (fixed > plain.fixed_unexplained && after < plain.wrong_before) plain = {m, fixed, plain.wrong_before, after};
    }
    const Displacement fast = find_displacement(ref, dec, cand, invariant, unexplained, plain.wrong_before);
    found += plain.fixed_unexplained > 0;
    EXPECT_EQ(fast.fixed_unexplained, plain.fixed_unexplained) << "round " << round;
    EXPECT_EQ(fast.wrong_before, plain.wrong_before) << "round " << round;
    EXPECT_EQ(fast.wrong_after, plain.wrong_after) << "round " << round;
    EXPECT_EQ(describe(fast.move), describe(plain.move)) << "round " << round;
  }
  EXPECT_GE(found, 10);
}

}  // namespace
}  // namespace shadowref::compare
