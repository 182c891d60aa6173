// visibility_test.cpp — soft shadows in visibility units on synthetic fractions: what is judged,
// the sampling tolerance, the explainer's band, cores, the mean-error bound, the verdict, and the
// candidate folder's visibility.png (present, missing, mis-sized).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

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

TEST(Visibility, TheSamplingTermsFollowFromTheGrids) {
  EXPECT_NEAR(kTolerance, 0.125 + 0.125 + 0.5 / 255, 1e-12);
  EXPECT_NEAR(kMeanBound, 0.0625, 1e-12);
  EXPECT_GT(visibility_sampling_tolerance(4, 8), kTolerance) << "a coarser reference tolerates more";
}

TEST(Visibility, TheSameFractionPassesWithNoError) {
  const auto r = ramp();
  const VisibilityComparison c = compare_visibility(r, grey(255), fraction(r), grey(255), kTolerance, kMeanBound, nullptr, 0);
  EXPECT_EQ(c.metrics.judged, static_cast<std::size_t>(kW * kH));
  EXPECT_EQ(c.metrics.penumbra, static_cast<std::size_t>((kW - 2) * kH)) << "0 and 1 are not penumbra";
  EXPECT_EQ(c.metrics.unexplained, 0u);
  EXPECT_LE(c.metrics.max_error, 0.5 / 255 + 1e-6);
  Judgement j;
  judge_visibility(c.metrics, j);
  EXPECT_EQ(j.verdict, Verdict::Pass);
}

TEST(Visibility, AnErrorWithinSamplingIsTolerated) {
  const auto r = ramp();
  const VisibilityComparison c =
      compare_visibility(r, grey(255), fraction(r, 0.2), grey(255), kTolerance, kMeanBound, nullptr, 0);
  EXPECT_EQ(c.metrics.beyond_sampling, 0u);
  EXPECT_EQ(c.metrics.unexplained, 0u);
  // ... but a uniform 0.2 over the whole penumbra is no sampling noise: the mean-error bound fails it.
  Judgement j;
  judge_visibility(c.metrics, j);
  EXPECT_EQ(j.verdict, Verdict::Fail);
  ASSERT_EQ(j.reasons.size(), 1u);
  EXPECT_NE(j.reasons[0].find("mean error over the penumbra"), std::string::npos) << j.reasons[0];
}

TEST(Visibility, ABlockBeyondSamplingIsAnUnexplainedCore) {
  const auto r = ramp();
  Image8 cand = fraction(r);
  for (int y = 2; y < 9; ++y)
    for (int x = 3; x < 10; ++x) cand.pixels[at(x, y)] = 255;  // lit where the penumbra is half dark
  const VisibilityComparison c = compare_visibility(r, grey(255), cand, grey(255), kTolerance, kMeanBound, nullptr, 0);
  EXPECT_GT(c.metrics.unexplained, 0u);
  EXPECT_GT(c.metrics.unexplained_core, 0u);
  Judgement j;
  judge_visibility(c.metrics, j);
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
  EXPECT_EQ(compare_visibility(r, grey(255), cand, grey(255), kTolerance, kMeanBound, &wide, 0).metrics.explained, 1u);
  const VisibilityComparison c = compare_visibility(r, grey(255), cand, grey(255), kTolerance, kMeanBound, &narrow, 0);
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
  const VisibilityComparison c = compare_visibility(r, covered, cand, mask, kTolerance, kMeanBound, nullptr, 0);
  EXPECT_EQ(c.metrics.judged, static_cast<std::size_t>(kW * kH - 3));
  EXPECT_EQ(c.metrics.unexplained, 0u);
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
    options.visibility_tolerance = {kTolerance};
    options.visibility_mean_error_bound = {kMeanBound};
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
  EXPECT_EQ(c.judgement.verdict, Verdict::Pass);
  const std::vector<std::string> written = write_error_images(c, root / "out");
  EXPECT_EQ(written, (std::vector<std::string>{"error.png", "visibility_error.png"}));
  // Without a tolerance the fraction is not judged (a light without an area).
  options.visibility_tolerance = {-1.0};
  c = compare_folders(root / "ref", root / "cand", kShadowMapPcf, options);
  EXPECT_FALSE(c.visibility_total.has_value());
}

}  // namespace
}  // namespace shadowref::compare
