// compare_test.cpp — the comparison on synthetic masks: counts by kind, undecided pixels ignored,
// regions, verdicts against each bound, refusal of bad input, and the error image's colours.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "shadowref/compare/compare.hpp"

namespace shadowref::compare {
namespace {

Image8 grey(int w, int h, std::uint8_t v) { return Image8{w, h, 1, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h), v)}; }
void set(Image8& i, int x, int y, std::uint8_t v) { i.pixels[static_cast<std::size_t>(y * i.width + x)] = v; }

TEST(CompareMask, IdenticalMasksHaveNoWrongPixels) {
  Image8 ref = grey(8, 8, 255);
  set(ref, 1, 1, 0);
  set(ref, 2, 2, 128);
  const MaskComparison c = compare_mask(ref, grey(8, 8, 255), ref);
  EXPECT_EQ(c.metrics.wrong, 0u);
  EXPECT_EQ(c.metrics.decided, 64u);
  EXPECT_EQ(c.metrics.decided_surface, 63u);
  EXPECT_EQ(c.metrics.regions, 0u);
  EXPECT_EQ(decide(c.metrics, kExactGeometry).verdict, Verdict::Pass);
}

TEST(CompareMask, CountsEachKindOnDecidedPixelsOnly) {
  Image8 ref = grey(10, 10, 255);
  for (int x = 0; x < 5; ++x) set(ref, x, 0, 0);  // a shadow strip in row 0
  set(ref, 9, 9, 128);                             // background corner
  Image8 dec = grey(10, 10, 255);
  Image8 cand = ref;
  set(cand, 5, 5, 0);    // false shadow
  set(cand, 0, 0, 255);  // false light
  set(cand, 9, 9, 255);  // coverage
  set(cand, 3, 3, 0);    // false shadow, but undecided: ignored
  set(dec, 3, 3, 0);
  const MaskComparison c = compare_mask(ref, dec, cand);
  EXPECT_EQ(c.metrics.false_shadow, 1u);
  EXPECT_EQ(c.metrics.false_light, 1u);
  EXPECT_EQ(c.metrics.coverage, 1u);
  EXPECT_EQ(c.metrics.wrong, 3u);
  EXPECT_EQ(c.metrics.decided, 99u);
  EXPECT_EQ(c.metrics.decided_surface, 98u);
  EXPECT_EQ(c.metrics.regions, 3u);
  EXPECT_EQ(c.metrics.largest_region, 1u);
  // Error image: kinds coloured, undecided tinted.
  const auto rgb = [&](int x, int y) {
    return std::array<int, 3>{c.error.at(x, y, 0), c.error.at(x, y, 1), c.error.at(x, y, 2)};
  };
  EXPECT_EQ(rgb(5, 5), (std::array<int, 3>{error_colour(ErrorClass::FalseShadow).data()[0], error_colour(ErrorClass::FalseShadow).data()[1], error_colour(ErrorClass::FalseShadow).data()[2]}));
  EXPECT_EQ(rgb(0, 0), (std::array<int, 3>{error_colour(ErrorClass::FalseLight).data()[0], error_colour(ErrorClass::FalseLight).data()[1], error_colour(ErrorClass::FalseLight).data()[2]}));
  EXPECT_EQ(rgb(9, 9), (std::array<int, 3>{error_colour(ErrorClass::Coverage).data()[0], error_colour(ErrorClass::Coverage).data()[1], error_colour(ErrorClass::Coverage).data()[2]}));
  EXPECT_EQ(rgb(3, 3), (std::array<int, 3>{error_colour(ErrorClass::Undecided).data()[0], error_colour(ErrorClass::Undecided).data()[1], error_colour(ErrorClass::Undecided).data()[2]}));
}

TEST(CompareMask, ValuesOtherThanTheThreeAreRefusedNotRounded) {
  const Image8 ref = grey(4, 4, 255);
  Image8 cand = grey(4, 4, 250);  // "almost lit": a broken writer, not a near miss
  set(cand, 0, 0, 10);
  try {
    (void)compare_mask(ref, grey(4, 4, 255), cand, "cand/mask.png");
    FAIL() << "a mask of 10 / 250 was accepted";
  } catch (const CompareError& e) {
    EXPECT_EQ(e.kind(), CompareError::Kind::BadInput);
    EXPECT_EQ(std::string(e.what()), "cand/mask.png: 16 pixel(s) hold values other than 255 (lit), 0 (shadowed) and 128 "
                                     "(no surface), e.g. 10 at (0, 0)");
  }
}

// The refusal comes first: a mask off the contract is refused before any wrong pixel is explained
// (the cause model is the costly part of a comparison).
TEST(CompareMask, OffContractValuesAreRefusedBeforeAnyCauseIsAsked) {
  const Image8 ref = grey(4, 4, 255);
  Image8 cand = grey(4, 4, 0);  // every pixel a false shadow...
  set(cand, 3, 3, 7);            // ...and one value off the contract
  int asked = 0;
  const Explainer explain = [&](std::size_t, int, int, bool) {
    ++asked;
    return Cause::TexelFootprint;
  };
  CompareOptions o;
  o.explain = &explain;
  EXPECT_THROW((void)compare_mask(ref, grey(4, 4, 255), cand, "cand/mask.png", 0, o), CompareError);
  EXPECT_EQ(asked, 0);
  set(cand, 3, 3, 0);
  EXPECT_EQ(compare_mask(ref, grey(4, 4, 255), cand, "cand/mask.png", 0, o).metrics.explained_texel, 16u);
  EXPECT_EQ(asked, 16);
}

TEST(CompareMask, RegionsAreEightConnected) {
  const Image8 ref = grey(20, 20, 255);
  Image8 cand = ref;
  for (int i = 0; i < 6; ++i) set(cand, i, i, 0);  // a diagonal: one 8-connected region of 6
  set(cand, 15, 2, 0);
  const MaskComparison c = compare_mask(ref, grey(20, 20, 255), cand);
  EXPECT_EQ(c.metrics.regions, 2u);
  EXPECT_EQ(c.metrics.largest_region, 6u);
}

TEST(Judge, EachBoundGivesItsVerdict) {
  const Threshold t{"test", true, 0.02, 0.5, "for the test"};
  MaskMetrics m;
  m.edge_pixels = 1000;
  m.unexplained = 20;  // 2 % of the edges: at the bound
  EXPECT_EQ(decide(m, t).verdict, Verdict::Pass);
  m.unexplained = 21;
  Decision j = decide(m, t);
  EXPECT_EQ(j.verdict, Verdict::Fail);
  ASSERT_EQ(j.reasons.size(), 1u);
  EXPECT_NE(j.reasons[0].find("unexplained wrong 21 px"), std::string::npos) << j.reasons[0];
  m.unexplained = 0;
  m.explained_texel = 400;
  m.explained_bias = 100;  // half the edges: at the quality bound
  EXPECT_EQ(decide(m, t).verdict, Verdict::Pass);
  m.explained_bias = 101;
  EXPECT_EQ(decide(m, t).verdict, Verdict::QualityWarning);
  m.unexplained_core = 1;  // one thick core is structural, whatever the ratios
  j = decide(m, t);
  EXPECT_EQ(j.verdict, Verdict::Fail);
  EXPECT_NE(j.reasons[0].find("core"), std::string::npos) << j.reasons[0];
}

// Several lights: each light's mask is decided alone. One light's shadows moved by a pixel (15
// displaced px of its 1000 edge pixels, 1.5 %) FAIL beside a correct light of 10 000 edge pixels,
// where their sum (15 of 11 000, 0.14 %) would pass; the reason names the light's mask.
TEST(Judge, EachLightIsDecidedAlone) {
  MaskMetrics correct, moved;
  correct.edge_pixels = 10000;
  moved.edge_pixels = 1000;
  moved.wrong = moved.unexplained = moved.displaced = 15;
  MaskMetrics total = correct;
  total += moved;
  EXPECT_EQ(decide(total, kShadowMap).verdict, Verdict::Pass) << "summed, the moved light hides behind the other's edges";
  const Decision d = decide_lights({correct, moved}, kShadowMap, {"mask_0.png", "mask_1.png"}, {"", "moved by (1, 0) px"});
  EXPECT_EQ(d.verdict, Verdict::Fail);
  ASSERT_EQ(d.reasons.size(), 1u);
  EXPECT_EQ(d.reasons[0].rfind("mask_1.png: 15 unexplained px", 0), 0u) << d.reasons[0];
  EXPECT_NE(d.reasons[0].find("moved by (1, 0) px"), std::string::npos) << d.reasons[0];
  // Both lights correct: PASS; one light alone: decide() itself, its reasons without a name.
  EXPECT_EQ(decide_lights({correct, correct}, kShadowMap, {"mask_0.png", "mask_1.png"}, {}).verdict, Verdict::Pass);
  const Decision one = decide_lights({moved}, kShadowMap, {"mask.png"}, {"moved by (1, 0) px"});
  ASSERT_EQ(one.reasons.size(), 1u);
  EXPECT_EQ(one.reasons[0], decide(moved, kShadowMap, "moved by (1, 0) px").reasons[0]);
}

TEST(Judge, UnexplainedErrorsWithoutAnyBoundaryAreAFailure) {
  MaskMetrics m;
  m.wrong = m.unexplained = 1;
  EXPECT_EQ(decide(m, kShadowMap).verdict, Verdict::Fail);
}

TEST(CompareMask, CountsEdgesAndThickCores) {
  // Left half lit, right half shadowed: one vertical boundary, two pixels wide in edge pixels.
  Image8 ref = grey(16, 16, 255);
  for (int y = 0; y < 16; ++y)
    for (int x = 8; x < 16; ++x) set(ref, x, y, 0);
  Image8 cand = ref;
  for (int y = 2; y < 10; ++y)  // an 8 x 8 swapped tile inside the lit half
    for (int x = 0; x < 8; ++x) set(cand, x, y, 0);
  const MaskComparison c = compare_mask(ref, grey(16, 16, 255), cand);
  EXPECT_EQ(c.metrics.edge_pixels, 32u);
  EXPECT_EQ(c.metrics.unexplained, 64u);
  // Core: the whole 5 × 5 block around it inside the image and wrong: x in 2..5 (x < 2 reaches the
  // border, x > 5 the right half, which is right), y in 4..7: 4 × 4 = 16.
  EXPECT_EQ(c.metrics.unexplained_core, 16u);
  EXPECT_EQ(decide(c.metrics, kShadowMap).verdict, Verdict::Fail);
}

// A local glitch is many unexplained pixels in one place. Along a long boundary (a 64-px edge, 128
// edge pixels), a run two pixels thick and 40 long is no glitch (the ratio bound is given room here:
// 80 px is 62 % of the edges), its densest 9 × 9
// window holds 18. 20 pixels packed in a 5 × 4 block FAIL by the window alone.
TEST(CompareMask, ALocalGlitchFailsWhereABoundaryRunDoesNot) {
  const Threshold roomy{"test", true, 1.0, 1.0, "a ratio bound out of the way"};
  Image8 ref = grey(64, 64, 255);
  for (int y = 32; y < 64; ++y)
    for (int x = 0; x < 64; ++x) set(ref, x, y, 0);
  Image8 run = ref;
  for (int y = 30; y < 32; ++y)  // two rows of false shadow above the boundary
    for (int x = 10; x < 50; ++x) set(run, x, y, 0);
  const MaskComparison thin = compare_mask(ref, grey(64, 64, 255), run);
  EXPECT_EQ(thin.metrics.unexplained, 80u);
  EXPECT_EQ(thin.metrics.densest_unexplained, 18u);
  EXPECT_EQ(thin.metrics.unexplained_core, 0u);
  // (A whole run so placed is a displaced shadow, which its own bound judges: not a glitch.)
  for (const std::string& reason : decide(thin.metrics, roomy).reasons)
    EXPECT_EQ(reason.find("local glitch"), std::string::npos) << "a run two pixels thick is no glitch: " << reason;

  Image8 blob = ref;
  for (int y = 10; y < 14; ++y)  // 4 rows of 5: no 5 x 5 core, all in one window
    for (int x = 20; x < 25; ++x) set(blob, x, y, 0);
  const MaskComparison glitch = compare_mask(ref, grey(64, 64, 255), blob);
  EXPECT_EQ(glitch.metrics.unexplained, 20u);
  EXPECT_EQ(glitch.metrics.unexplained_core, 0u);
  EXPECT_EQ(glitch.metrics.densest_unexplained, 20u);
  const Decision d = decide(glitch.metrics, roomy);
  EXPECT_EQ(d.verdict, Verdict::Fail);
  ASSERT_EQ(d.reasons.size(), 1u);
  EXPECT_NE(d.reasons[0].find("local glitch"), std::string::npos) << d.reasons[0];
  // Exact techniques have no band for a tile to hide in, and a terminator's z-fight wedge that grows
  // with the resolution: the bound is the banded families' (thresholds.hpp).
  const Threshold exact{"test-exact", false, 1.0, 1.0, "no bands, a ratio bound out of the way"};
  EXPECT_EQ(decide(glitch.metrics, exact).verdict, Verdict::Pass);
}

TEST(CompareMask, AnExplainerTakesErrorsOutOfTheUnexplainedAndColoursThem) {
  Image8 ref = grey(8, 8, 255);
  Image8 cand = ref;
  set(cand, 2, 2, 0);
  set(cand, 5, 5, 0);
  int asked = 0;
  const Explainer explain = [&](std::size_t light, int x, int, bool candidate_lit) {
    ++asked;
    EXPECT_EQ(light, 3u);
    EXPECT_FALSE(candidate_lit);
    return x == 2 ? Cause::TexelFootprint : Cause::DepthBias;
  };
  CompareOptions o;
  o.explain = &explain;
  const MaskComparison c = compare_mask(ref, grey(8, 8, 255), cand, "mask", 3, o);
  EXPECT_EQ(asked, 2);
  EXPECT_EQ(c.metrics.explained_texel, 1u);
  EXPECT_EQ(c.metrics.explained_bias, 1u);
  EXPECT_EQ(c.metrics.unexplained, 0u);
  EXPECT_EQ(c.error.at(2, 2, 0), error_colour(ErrorClass::Texel).data()[0]);
  EXPECT_EQ(c.error.at(5, 5, 2), error_colour(ErrorClass::Bias).data()[2]);
}

TEST(CompareMask, TheNoCastShadowInvariantJudgesUndecidedPixelsToo) {
  const Image8 ref = grey(8, 8, 255);
  Image8 cand = ref;
  set(cand, 3, 3, 0);                    // a false shadow on an undecided pixel
  const Image8 undecided = grey(8, 8, 0);
  EXPECT_EQ(compare_mask(ref, undecided, cand).metrics.wrong, 0u);
  CompareOptions o;
  o.no_cast_shadow_invariant = true;
  const MaskComparison c = compare_mask(ref, undecided, cand, "mask", 0, o);
  EXPECT_EQ(c.metrics.wrong, 1u);
  EXPECT_EQ(c.metrics.invariant_pixels, 1u);
  EXPECT_EQ(decide(c.metrics, kExactGeometry).verdict, Verdict::Fail);
}

TEST(Thresholds, EveryRendererTechniqueHasOneAndEachHasAReason) {
  for (const char* t : {"planar", "volume-zpass", "volume-zfail", "volume-zfail-clamp", "volume-robust",
                        "volume-finite"})
    EXPECT_EQ(&threshold_for(t), &kExactGeometry) << t;
  EXPECT_EQ(&threshold_for("shadowmap"), &kShadowMap);
  EXPECT_EQ(&threshold_for("shadowmap-rgba8"), &kShadowMap);
  EXPECT_EQ(&threshold_for("shadowmap-pcf"), &kShadowMapPcf);
  EXPECT_EQ(&threshold_for("csm-pcf"), &kShadowMapPcf);
  EXPECT_EQ(&threshold_for("pcss"), &kSoftShadow);
  EXPECT_EQ(&threshold_for("an-engine-technique"), &kExactGeometry);
  EXPECT_FALSE(kExactGeometry.bands) << "exact techniques get no texel or bias band";
  for (const Threshold* t : all_thresholds()) {
    EXPECT_FALSE(t->why.empty()) << t->name;
    EXPECT_GT(t->unexplained_fail, 0.0) << t->name;
  }
}

TEST(CompareMask, SizeMismatchIsItsOwnError) {
  try {
    compare_mask(grey(4, 4, 255), grey(4, 4, 255), grey(4, 5, 255));
    FAIL() << "no exception";
  } catch (const CompareError& e) {
    EXPECT_EQ(e.kind(), CompareError::Kind::SizeMismatch);
    EXPECT_NE(std::string(e.what()).find("4x5"), std::string::npos);
  }
}

class Folders : public ::testing::Test {
 protected:
  void SetUp() override {
    root = std::filesystem::temp_directory_path() /
           ("shadowref-compare-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(root);
    std::filesystem::create_directories(root / "ref");
    std::filesystem::create_directories(root / "cand");
  }
  void TearDown() override { std::filesystem::remove_all(root); }
  std::filesystem::path root;
};

TEST_F(Folders, ComparesAndWritesErrorImages) {
  Image8 ref = grey(16, 8, 255);
  set(ref, 3, 3, 0);
  outputs::write_png(ref, root / "ref" / "mask.png");
  outputs::write_png(grey(16, 8, 255), root / "ref" / "decided.png");
  outputs::write_png(grey(16, 8, 255), root / "cand" / "mask.png");
  const FolderComparison c = compare_folders(root / "ref", root / "cand", kExactGeometry);
  EXPECT_EQ(c.total.false_light, 1u);
  EXPECT_EQ(c.masks, std::vector<std::string>{"mask.png"});
  EXPECT_EQ(write_error_images(c, root / "out"), std::vector<std::string>{"error.png"});
  const Image8 e = read_image8(root / "out" / "error.png", 3);
  EXPECT_EQ(e.at(3, 3, 2), error_colour(ErrorClass::FalseLight).data()[2]);
}

TEST_F(Folders, SeveralLightsAreSummedAndAMissingOneRefused) {
  for (int i = 0; i < 2; ++i) {
    outputs::write_png(grey(4, 4, 255), root / "ref" / ("mask_" + std::to_string(i) + ".png"));
    outputs::write_png(grey(4, 4, 255), root / "ref" / ("decided_" + std::to_string(i) + ".png"));
  }
  outputs::write_png(grey(4, 4, 0), root / "cand" / "mask_0.png");
  EXPECT_THROW(compare_folders(root / "ref", root / "cand", kExactGeometry), CompareError);
  outputs::write_png(grey(4, 4, 255), root / "cand" / "mask_1.png");
  const FolderComparison c = compare_folders(root / "ref", root / "cand", kExactGeometry);
  EXPECT_EQ(c.total.false_shadow, 16u);
  EXPECT_EQ(c.total.decided_surface, 32u);
  EXPECT_EQ(c.decision.verdict, Verdict::Fail);
}

TEST_F(Folders, RefusesBadFiles) {
  outputs::write_png(grey(4, 4, 255), root / "ref" / "mask.png");
  outputs::write_png(grey(4, 4, 255), root / "ref" / "decided.png");
  const auto kind_of = [&] {
    try {
      compare_folders(root / "ref", root / "cand", kExactGeometry);
    } catch (const CompareError& e) {
      return e.kind();
    }
    ADD_FAILURE() << "no exception";
    return CompareError::Kind::SizeMismatch;
  };
  EXPECT_EQ(kind_of(), CompareError::Kind::BadInput);  // missing candidate
  Image8 rgb{4, 4, 3, std::vector<std::uint8_t>(48, 255)};
  outputs::write_png(rgb, root / "cand" / "mask.png");
  EXPECT_EQ(kind_of(), CompareError::Kind::BadInput);  // three channels
  outputs::write_png(grey(4, 4, 255), root / "cand" / "mask.png");
  {
    // Truncate a valid PNG of the right size inside its pixel data: the 12-byte IEND chunk and
    // the last 8 bytes of IDAT go, the header stays (so the size check passes and decoding fails).
    const auto size = std::filesystem::file_size(root / "cand" / "mask.png");
    std::filesystem::resize_file(root / "cand" / "mask.png", size - 20);
  }
  EXPECT_EQ(kind_of(), CompareError::Kind::BadInput);  // truncated
  {
    std::ofstream f(root / "cand" / "mask.png");
    f << "not a png";
  }
  EXPECT_EQ(kind_of(), CompareError::Kind::BadInput);  // garbage
  outputs::write_png(grey(5, 4, 255), root / "cand" / "mask.png");
  EXPECT_EQ(kind_of(), CompareError::Kind::SizeMismatch);
}

}  // namespace
}  // namespace shadowref::compare

namespace shadowref::compare {
namespace {

// The comparison's definition written plainly, pixel by pixel (as compare_mask was before its
// single pass was vectorised): the oracle the fast pass must equal, count for count and byte for
// byte in the error image.
MaskComparison plain_compare(const Image8& ref, const Image8& dec, const Image8& cand, const CompareOptions& o) {
  const int w = ref.width, h = ref.height;
  const auto cls = [](std::uint8_t v) { return v < 64 ? 0 : v < 192 ? 1 : 2; };  // shadowed, none, lit
  const auto at = [&](const Image8& i, int x, int y) { return i.pixels[static_cast<std::size_t>(y * w + x)]; };
  MaskComparison out;
  MaskMetrics& m = out.metrics;
  m.width = w, m.height = h, m.pixels = static_cast<std::size_t>(w * h);
  out.error = Image8{w, h, 3, std::vector<std::uint8_t>(3 * m.pixels)};
  std::vector<std::uint8_t> codes(m.pixels), unexplained(m.pixels);
  static constexpr std::uint8_t kDim[3][3] = {{55, 55, 55}, {28, 28, 42}, {150, 150, 150}};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int r = cls(at(ref, x, y)), c = cls(at(cand, x, y));
      for (const auto& [nx, ny] : {std::pair{x - 1, y}, std::pair{x + 1, y}, std::pair{x, y - 1}, std::pair{x, y + 1}})
        if (nx >= 0 && ny >= 0 && nx < w && ny < h && cls(at(ref, nx, ny)) != r) {
          ++m.edge_pixels;
          break;
        }
      const std::uint8_t v = at(cand, x, y);
      m.off_values += v != 0 && v != 128 && v != 255;
      const bool decided = at(dec, x, y) >= 128;
      const bool invariant = !decided && o.no_cast_shadow_invariant && r == 2 && c == 0;
      const unsigned char* colour = kDim[r];
      if (!decided && !invariant) {
        colour = error_colour(ErrorClass::Undecided).data();
      } else {
        m.decided += decided;
        m.decided_surface += decided && r != 1;
        m.invariant_pixels += invariant;
        if (r != c) {
          ++m.wrong;
          std::uint8_t code = 3;
          if (r == 1 || c == 1) {
            ++m.coverage, colour = error_colour(ErrorClass::Coverage).data();
          } else if (r == 2) {
            ++m.false_shadow, colour = error_colour(ErrorClass::FalseShadow).data(), code = 1;
          } else {
            ++m.false_light, colour = error_colour(ErrorClass::FalseLight).data(), code = 2;
          }
          codes[static_cast<std::size_t>(y * w + x)] = code;
          const Cause cause = code != 3 && o.explain ? (*o.explain)(0, x, y, c == 2) : Cause::Unexplained;
          if (cause == Cause::TexelFootprint) {
            ++m.explained_texel, colour = error_colour(ErrorClass::Texel).data();
          } else if (cause == Cause::DepthBias) {
            ++m.explained_bias, colour = error_colour(ErrorClass::Bias).data();
          } else {
            ++m.unexplained;
            m.unexplained_false_light += code == 2;
            if (cause == Cause::Acne) ++m.unexplained_acne, colour = error_colour(ErrorClass::Acne).data();
            unexplained[static_cast<std::size_t>(y * w + x)] = 1;
          }
        }
      }
      for (int k = 0; k < 3; ++k) out.error.pixels[3 * static_cast<std::size_t>(y * w + x) + static_cast<std::size_t>(k)] = colour[k];
    }
  m.unexplained_core = count_cores(unexplained, w, h, m.unexplained);
  for (std::size_t i = 0; i < m.pixels; ++i) unexplained[i] = unexplained[i] && codes[i] == 2;
  m.unexplained_false_light_core = count_cores(unexplained, w, h, m.unexplained_false_light);
  // Regions: a plain union of 8-neighbours by repeated flood fill.
  std::vector<std::size_t> stack;
  for (std::size_t s = 0; s < m.pixels; ++s) {
    if (!codes[s]) continue;
    std::size_t size = 0;
    codes[s] = 0;
    stack.push_back(s);
    while (!stack.empty()) {
      const std::size_t p = stack.back();
      stack.pop_back();
      ++size;
      const int px = static_cast<int>(p) % w, py = static_cast<int>(p) / w;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int qx = px + dx, qy = py + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const std::size_t q = static_cast<std::size_t>(qy * w + qx);
          if (codes[q]) codes[q] = 0, stack.push_back(q);
        }
    }
    ++m.regions;
    m.largest_region = std::max(m.largest_region, size);
  }
  return out;
}

void expect_same(const MaskMetrics& a, const MaskMetrics& b) {
  EXPECT_EQ(a.decided, b.decided);
  EXPECT_EQ(a.decided_surface, b.decided_surface);
  EXPECT_EQ(a.wrong, b.wrong);
  EXPECT_EQ(a.false_shadow, b.false_shadow);
  EXPECT_EQ(a.false_light, b.false_light);
  EXPECT_EQ(a.coverage, b.coverage);
  EXPECT_EQ(a.off_values, b.off_values);
  EXPECT_EQ(a.regions, b.regions);
  EXPECT_EQ(a.largest_region, b.largest_region);
  EXPECT_EQ(a.explained_texel, b.explained_texel);
  EXPECT_EQ(a.explained_bias, b.explained_bias);
  EXPECT_EQ(a.unexplained, b.unexplained);
  EXPECT_EQ(a.unexplained_false_light, b.unexplained_false_light);
  EXPECT_EQ(a.unexplained_acne, b.unexplained_acne);
  EXPECT_EQ(a.unexplained_core, b.unexplained_core);
  EXPECT_EQ(a.unexplained_false_light_core, b.unexplained_false_light_core);
  EXPECT_EQ(a.edge_pixels, b.edge_pixels);
  EXPECT_EQ(a.invariant_pixels, b.invariant_pixels);
}

// Masks of blobs and noise at odd sizes (row ends, one-pixel images), with and without the
// invariant and an explainer that gives every cause: the fast pass equals the plain definition.
TEST(CompareMask, FastPassEqualsThePlainDefinition) {
  std::uint32_t state = 12345;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  const Explainer explain = [](std::size_t, int x, int y, bool) {
    return static_cast<Cause>((x * 7 + y * 3) % 4 == 0 ? 0 : (x + y) % 4);
  };
  ASSERT_EQ(static_cast<int>(Cause::Unexplained), 0);
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{1, 9}, std::pair{9, 1}, std::pair{37, 23}, std::pair{64, 64}}) {
    for (int round = 0; round < 6; ++round) {
      Image8 ref = grey(w, h, 255), dec = grey(w, h, 255), cand = grey(w, h, 255);
      const std::uint8_t values[3] = {0, 128, 255};
      for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
        const int x = static_cast<int>(i) % w, y = static_cast<int>(i) / w;
        ref.pixels[i] = (x - w / 2) * (x - w / 2) + (y - h / 2) * (y - h / 2) < w * h / 6 ? 0 : (y < h / 6 ? 128 : 255);
        cand.pixels[i] = next() % 5 == 0 ? values[next() % 3] : ref.pixels[i];
        if (round % 2 && (x / 5 + y / 5) % 3 == 0) cand.pixels[i] = 0;  // thick blobs: cores
        dec.pixels[i] = round >= 4 && next() % 7 == 0 ? 0 : 255;
      }
      CompareOptions o;
      o.no_cast_shadow_invariant = round % 3 == 0;
      if (round >= 2) o.explain = &explain;
      const MaskComparison fast = compare_mask(ref, dec, cand, "mask", 0, o);
      const MaskComparison plain = plain_compare(ref, dec, cand, o);
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " round " + std::to_string(round));
      expect_same(fast.metrics, plain.metrics);
      EXPECT_EQ(fast.error.pixels, plain.error.pixels);
      // Without its error image (the probes' comparison): the same counts, no image.
      CompareOptions counts_only = o;
      counts_only.error_image = false;
      const MaskComparison unpainted = compare_mask(ref, dec, cand, "mask", 0, counts_only);
      expect_same(unpainted.metrics, plain.metrics);
      EXPECT_TRUE(unpainted.error.pixels.empty());
      if (w == 64 && round == 1) {
        EXPECT_GT(plain.metrics.unexplained_core, 0u) << "the oracle must see cores";
      }
    }
  }
}

}  // namespace
}  // namespace shadowref::compare
