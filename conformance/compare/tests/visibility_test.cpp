// visibility_test.cpp — soft shadows in visibility units on synthetic fractions: what is judged,
// the sampling tolerance, the explainer's band, cores, the mean-error bound, the verdict, and the
// candidate folder's visibility.png (present, missing, mis-sized).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "shadowref/compare/compare.hpp"
#include "shadowref/outputs/file_names.hpp"

namespace shadowref::compare {
namespace {

constexpr int kW = 16, kH = 12;

Image8 grey(std::uint8_t v) { return Image8{kW, kH, 1, std::vector<std::uint8_t>(kW * kH, v)}; }
std::size_t at(int x, int y) { return static_cast<std::size_t>(y * kW + x); }

// A penumbra: the reference's fraction ramps from 0 (x = 0) to 1 (x = 15) across the image.
std::vector<float> ramp() {
  std::vector<float> r(kW * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) r[at(x, y)] = static_cast<float>(x) / (kW - 1);
  return r;
}
// The candidate's 8-bit fraction of `f` shifted by `offset`.
Image8 fraction(const std::vector<float>& f, double offset = 0) {
  Image8 img = grey(0);
  for (std::size_t i = 0; i < f.size(); ++i)
    img.pixels[i] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(static_cast<double>(f[i]) + offset, 0.0, 1.0)));
  return img;
}

const double kTolerance = visibility_sampling_tolerance(8, 8);
const double kMeanBound = visibility_mean_error_bound(8, 8);
const VisibilityBounds kGrid = visibility_bounds(8, 8, outputs::Sampling::Grid);

TEST(Visibility, TheSamplingTermsFollowFromTheGrids) {
  EXPECT_NEAR(kTolerance, 0.125 + 0.125 + 0.5 / 255, 1e-12);
  EXPECT_NEAR(kMeanBound, 0.0625, 1e-12);
  EXPECT_GT(visibility_sampling_tolerance(4, 8), kTolerance) << "a coarser reference tolerates more";
}

TEST(Visibility, TheSameFractionPassesWithNoError) {
  const auto r = ramp();
  const VisibilityComparison c = compare_visibility(r, grey(255), fraction(r), grey(255), kGrid, nullptr, 0);
  EXPECT_EQ(c.metrics.judged, static_cast<std::size_t>(kW * kH));
  EXPECT_EQ(c.metrics.penumbra, static_cast<std::size_t>((kW - 2) * kH)) << "0 and 1 are not penumbra";
  EXPECT_EQ(c.metrics.unexplained, 0u);
  EXPECT_LE(c.metrics.max_error, 0.5 / 255 + 1e-6);
  Decision j;
  decide_visibility(c.metrics, j);
  EXPECT_EQ(j.verdict, Verdict::Pass);
}

TEST(Visibility, AnErrorWithinSamplingIsTolerated) {
  const auto r = ramp();
  const VisibilityComparison c =
      compare_visibility(r, grey(255), fraction(r, 0.2), grey(255), kGrid, nullptr, 0);
  EXPECT_EQ(c.metrics.beyond_sampling, 0u);
  EXPECT_EQ(c.metrics.unexplained, 0u);
  // ... but a uniform 0.2 over the whole penumbra is no sampling noise: the mean-error bound fails it.
  Decision j;
  decide_visibility(c.metrics, j);
  EXPECT_EQ(j.verdict, Verdict::Fail);
  ASSERT_EQ(j.reasons.size(), 1u);
  EXPECT_NE(j.reasons[0].find("mean error over the penumbra"), std::string::npos) << j.reasons[0];
}

TEST(Visibility, ABlockBeyondSamplingIsAnUnexplainedCore) {
  const auto r = ramp();
  Image8 cand = fraction(r);
  for (int y = 2; y < 9; ++y)
    for (int x = 3; x < 10; ++x) cand.pixels[at(x, y)] = 255;  // lit where the penumbra is half dark
  const VisibilityComparison c = compare_visibility(r, grey(255), cand, grey(255), kGrid, nullptr, 0);
  EXPECT_GT(c.metrics.unexplained, 0u);
  EXPECT_GT(c.metrics.unexplained_core, 0u);
  Decision j;
  decide_visibility(c.metrics, j);
  EXPECT_EQ(j.verdict, Verdict::Fail);
  // Too light: the false-light colour.
  EXPECT_EQ(c.error.at(6, 5, 2) > c.error.at(6, 5, 0), true);
}

TEST(Visibility, TheExplainersRangeExplainsAndOnlyItsRange) {
  const auto r = ramp();
  Image8 cand = fraction(r);
  cand.pixels[at(7, 6)] = 255;  // reference 7/15: 0.53 too light
  const VisibilityExplainer wide = [](std::size_t, int, int) { return std::make_pair(0.0, 1.0); };
  const VisibilityExplainer narrow = [](std::size_t, int, int) { return std::make_pair(0.4, 0.6); };
  EXPECT_EQ(compare_visibility(r, grey(255), cand, grey(255), kGrid, &wide, 0).metrics.explained, 1u);
  const VisibilityComparison c = compare_visibility(r, grey(255), cand, grey(255), kGrid, &narrow, 0);
  EXPECT_EQ(c.metrics.explained, 0u);
  EXPECT_EQ(c.metrics.unexplained, 1u);
}

TEST(Visibility, PixelsNotCoveredByOneSurfaceOrWithoutOneAreNotJudged) {
  auto r = ramp();
  Image8 covered = grey(255), mask = grey(255), cand = fraction(r);
  covered.pixels[at(5, 5)] = 0;      // an edge crosses it
  cand.pixels[at(5, 5)] = 255;
  mask.pixels[at(6, 6)] = outputs::kMaskNoSurface;  // the candidate sees no surface
  cand.pixels[at(6, 6)] = 0;
  r[at(7, 7)] = -1;                  // nor does the reference
  const VisibilityComparison c = compare_visibility(r, covered, cand, mask, kGrid, nullptr, 0);
  EXPECT_EQ(c.metrics.judged, static_cast<std::size_t>(kW * kH - 3));
  EXPECT_EQ(c.metrics.unexplained, 0u);
}

// Randomized kernels ("sampling": "random"): a wider image, whose penumbra has room for statistics.
// The reference ramps from 0 to 1 over kRandomW columns.
constexpr int kRandomW = 96, kRandomH = 64;
std::vector<float> wide_ramp(double width_scale = 1.0) {
  std::vector<float> r(kRandomW * kRandomH);
  for (int y = 0; y < kRandomH; ++y)
    for (int x = 0; x < kRandomW; ++x)
      r[static_cast<std::size_t>(y * kRandomW + x)] = static_cast<float>(
          std::clamp(0.5 + (static_cast<double>(x) / (kRandomW - 1) - 0.5) / width_scale, 0.0, 1.0));
  return r;
}
Image8 wide_grey(std::uint8_t v) { return Image8{kRandomW, kRandomH, 1, std::vector<std::uint8_t>(kRandomW * kRandomH, v)}; }
// A random estimator of `truth` with `taps` taps per pixel: each tap lit with probability f, from
// std::mt19937 (its output sequence is fixed by the standard: the same image on every platform).
Image8 random_estimate(const std::vector<float>& truth, int taps, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Image8 img = wide_grey(0);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    int lit = 0;
    for (int t = 0; t < taps; ++t) lit += static_cast<double>(rng()) / 4294967296.0 < static_cast<double>(truth[i]);
    img.pixels[i] = static_cast<std::uint8_t>(std::lround(255.0 * lit / taps));
  }
  return img;
}
Decision judged(const VisibilityComparison& c) {
  Decision j;
  decide_visibility(c.metrics, j);
  return j;
}
bool says(const Decision& j, const char* what) {
  for (const std::string& r : j.reasons)
    if (r.find(what) != std::string::npos) return true;
  return false;
}

TEST(VisibilityRandom, TheBoundsFollowFromTheBinomialSpread) {
  // 16 taps (4 per axis): sigma <= 1/(2 * 4).
  const VisibilityBounds b = visibility_bounds(8, 4, outputs::Sampling::Random);
  EXPECT_NEAR(b.tolerance, 1.0 / 8 + 3.0 / 8 + 0.5 / 255, 1e-12);
  EXPECT_NEAR(b.mean_error_bound, 1.0 / 32 + 1.0 / 8, 1e-12);
  EXPECT_NEAR(b.local_mean_error_bound, 1.0 / 32 + 1.0 / 24, 1e-12);
  EXPECT_EQ(visibility_bounds(8, 4, outputs::Sampling::Grid).local_mean_error_bound, 0.0) << "a grid has no local rule";
}

TEST(VisibilityRandom, AnHonestRandomEstimatePassesDeclaredRandom) {
  const auto r = wide_ramp();
  const Image8 cand = random_estimate(r, 16, 1);
  const VisibilityComparison c =
      compare_visibility(r, wide_grey(255), cand, wide_grey(255), visibility_bounds(8, 4, outputs::Sampling::Random), nullptr, 0);
  const Decision j = judged(c);
  EXPECT_EQ(j.verdict, Verdict::Pass) << (j.reasons.empty() ? "" : j.reasons[0]);
  // Its noise is what the binomial says (E|e| ~ 0.8 sigma, sigma = sqrt(f (1 - f) / 16) averaged
  // over the ramp: 0.8 * 0.39 / 4 = 0.079), and the local means remove two thirds of it.
  EXPECT_GT(c.metrics.mean_penumbra_error(), 0.05);
  EXPECT_LT(c.metrics.mean_penumbra_local_error(), 0.5 * c.metrics.mean_penumbra_error());
}

TEST(VisibilityRandom, AWrongWidthFailsUnderRandomSampling) {
  // Half the penumbra's width (a light of half the size), estimated as honestly as above.
  const auto truth = wide_ramp();
  const Image8 cand = random_estimate(wide_ramp(0.5), 16, 2);
  const Decision j = judged(compare_visibility(truth, wide_grey(255), cand, wide_grey(255),
                                                visibility_bounds(8, 4, outputs::Sampling::Random), nullptr, 0));
  EXPECT_EQ(j.verdict, Verdict::Fail);
  EXPECT_TRUE(says(j, "wrong width")) << (j.reasons.empty() ? "" : j.reasons[0]);
}

TEST(VisibilityRandom, NoiseALocalMeanRemovesIsAWarningNotAWrongWidth) {
  // A checkerboard of +-0.2 about the truth: beyond the declared taps' spread pixel by pixel
  // (0.2 > 1/32 + 1/8), yet its 3x3 local means are right to 0.2/9.
  const auto r = wide_ramp();
  std::vector<float> noisy(r);
  for (int y = 0; y < kRandomH; ++y)
    for (int x = 0; x < kRandomW; ++x) noisy[static_cast<std::size_t>(y * kRandomW + x)] += (x + y) % 2 ? 0.2f : -0.2f;
  Image8 cand = wide_grey(0);
  for (std::size_t i = 0; i < r.size(); ++i)
    cand.pixels[i] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(static_cast<double>(noisy[i]), 0.0, 1.0)));
  const Decision random = judged(compare_visibility(r, wide_grey(255), cand, wide_grey(255),
                                                     visibility_bounds(8, 4, outputs::Sampling::Random), nullptr, 0));
  EXPECT_EQ(random.verdict, Verdict::QualityWarning);
  EXPECT_TRUE(says(random, "noise")) << (random.reasons.empty() ? "" : random.reasons[0]);
  EXPECT_FALSE(says(random, "wrong width"));
  // Declared a grid, the same pixels are a wrong penumbra: the declaration is what says "noise".
  const Decision grid = judged(compare_visibility(r, wide_grey(255), cand, wide_grey(255),
                                                   visibility_bounds(8, 4, outputs::Sampling::Grid), nullptr, 0));
  EXPECT_EQ(grid.verdict, Verdict::Fail);
}

// The map's texels (visibility.hpp): where a light's mean error exceeds sampling's bound, each
// penumbra pixel's texel shift is asked, and half its mean joins the bound in quadrature.
TEST(VisibilityTexels, AreAskedOnlyWhereTheMeanExceedsSampling) {
  const auto r = ramp();
  int asked = 0;
  const VisibilityTexelShift shift = [&asked](std::size_t, int, int) { return ++asked, 0.2; };
  const VisibilityComparison c = compare_visibility(r, grey(255), fraction(r), grey(255), kGrid, nullptr, 0, &shift);
  EXPECT_EQ(asked, 0) << "a fraction within sampling needs no texel";
  EXPECT_EQ(c.metrics.mean_penumbra_texel_error(), 0.0);
  EXPECT_DOUBLE_EQ(c.metrics.mean_error_fail(), kMeanBound);
}

TEST(VisibilityTexels, ForgiveAPenumbraAFewTexelsWide) {
  // Every penumbra pixel 0.1 too light: beyond sampling's mean bound (0.0625), within its pixel
  // tolerance. A map whose half texel moves the truth by 0.2 here (a penumbra 2.5 texels wide) may
  // honestly leave 0.1 on average: hypot(0.0625, 0.1) = 0.118 holds it.
  const auto r = ramp();
  const Image8 cand = fraction(r, 0.1);
  int asked = 0;
  const VisibilityTexelShift coarse = [&asked](std::size_t, int, int) { return ++asked, 0.2; };
  const VisibilityComparison c = compare_visibility(r, grey(255), cand, grey(255), kGrid, nullptr, 0, &coarse);
  EXPECT_EQ(asked, static_cast<int>(c.metrics.penumbra)) << "each penumbra pixel asked once";
  EXPECT_NEAR(c.metrics.mean_penumbra_texel_error(), 0.1, 1e-12);
  EXPECT_NEAR(c.metrics.mean_error_fail(), std::hypot(kMeanBound, 0.1), 1e-12);
  Decision j;
  decide_visibility(c.metrics, j);
  EXPECT_EQ(j.verdict, Verdict::Pass) << (j.reasons.empty() ? "" : j.reasons[0]);
  // Without a map (no texel shift) the same pixels are a wrong penumbra.
  Decision without;
  decide_visibility(compare_visibility(r, grey(255), cand, grey(255), kGrid, nullptr, 0).metrics, without);
  EXPECT_EQ(without.verdict, Verdict::Fail);
}

TEST(VisibilityTexels, DoNotForgiveAWrongWidthAFineMapResolves) {
  // The same error where the map's half texel moves the truth by only 0.02: FAIL, the texel error named.
  const auto r = ramp();
  const VisibilityTexelShift fine = [](std::size_t, int, int) { return 0.02; };
  Decision j;
  decide_visibility(compare_visibility(r, grey(255), fraction(r, 0.1), grey(255), kGrid, nullptr, 0, &fine).metrics, j);
  EXPECT_EQ(j.verdict, Verdict::Fail);
  EXPECT_TRUE(says(j, "texel error 0.010")) << (j.reasons.empty() ? "" : j.reasons[0]);
}

class VisibilityFolders : public ::testing::Test {
 protected:
  void SetUp() override {
    root = std::filesystem::temp_directory_path() /
           ("shadowref-visibility-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(root);
    std::filesystem::create_directories(root / "ref");
    std::filesystem::create_directories(root / "cand");
    const auto r = ramp();
    Image8 mask = grey(255);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW / 2; ++x) mask.pixels[at(x, y)] = 0;
    outputs::write_png(mask, root / "ref" / "mask.png");
    outputs::write_png(grey(255), root / "ref" / "decided.png");
    outputs::write_png(grey(255), root / "ref" / outputs::kCoveredName);
    outputs::write_exr(kW, kH, r.data(), root / "ref" / "visibility.exr");
    outputs::write_png(mask, root / "cand" / "mask.png");
    options.visibility = {visibility_bounds(8, 8, outputs::Sampling::Grid)};
  }
  void TearDown() override { std::filesystem::remove_all(root); }
  std::filesystem::path root;
  CompareOptions options;
};

TEST_F(VisibilityFolders, ASoftCandidateNeedsItsVisibilityPng) {
  try {
    compare_folders(root / "ref", root / "cand", kShadowMapPcf, options);
    FAIL() << "no exception";
  } catch (const CompareError& e) {
    EXPECT_EQ(e.kind(), CompareError::Kind::BadInput);
    EXPECT_NE(std::string(e.what()).find("visibility.png: no such file"), std::string::npos) << e.what();
  }
  outputs::write_png(Image8{kW + 1, kH, 1, std::vector<std::uint8_t>((kW + 1) * kH, 0)}, root / "cand" / "visibility.png");
  EXPECT_THROW(compare_folders(root / "ref", root / "cand", kShadowMapPcf, options), CompareError) << "mis-sized";
}

TEST_F(VisibilityFolders, JudgesTheFractionAndWritesItsErrorImage) {
  outputs::write_png(fraction(ramp()), root / "cand" / "visibility.png");
  FolderComparison c = compare_folders(root / "ref", root / "cand", kShadowMapPcf, options);
  ASSERT_TRUE(c.visibility_total.has_value());
  EXPECT_EQ(c.visibility_total->unexplained, 0u);
  EXPECT_EQ(c.decision.verdict, Verdict::Pass);
  const std::vector<std::string> written = write_error_images(c, root / "out");
  EXPECT_EQ(written, (std::vector<std::string>{"error.png", "visibility_error.png"}));
  // Without a tolerance the fraction is not judged (a light without an area).
  options.visibility = {VisibilityBounds{}};
  c = compare_folders(root / "ref", root / "cand", kShadowMapPcf, options);
  EXPECT_FALSE(c.visibility_total.has_value());
}

}  // namespace
}  // namespace shadowref::compare
