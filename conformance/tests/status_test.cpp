// status_test.cpp — the status rules (conform/status.hpp) on their own: every verdict under every
// expectation, every exit code, unmet expectations, and the predicted-errors signature.
#include <gtest/gtest.h>

#include "shadowref/conform/status.hpp"

namespace shadowref::conform {
namespace {

using compare::Verdict;

TEST(Status, EveryVerdictUnderEveryExpectation) {
  EXPECT_EQ(status_of(Verdict::Pass, true), Status::Pass);
  EXPECT_EQ(status_of(Verdict::QualityWarning, true), Status::Warn);
  EXPECT_EQ(status_of(Verdict::Fail, true), Status::Fail);
  EXPECT_EQ(status_of(Verdict::Fail, false), Status::XFail);
  // An expected failure that passes or merely warns: the limitation did not show.
  EXPECT_EQ(status_of(Verdict::Pass, false), Status::XPass);
  EXPECT_EQ(status_of(Verdict::QualityWarning, false), Status::XPass);
}

TEST(Status, FailuresAreFailXPassAndError) {
  for (Status s : {Status::Fail, Status::XPass, Status::Error}) EXPECT_TRUE(is_failure(s)) << to_string(s);
  for (Status s : {Status::Pass, Status::Warn, Status::XFail}) EXPECT_FALSE(is_failure(s)) << to_string(s);
}

TEST(Status, ExitCodes) {
  EXPECT_EQ(exit_code({}, {}), 0);
  EXPECT_EQ(exit_code({Status::Pass, Status::XFail}, {false, false}), 0);
  EXPECT_EQ(exit_code({Status::Pass, Status::Warn}, {false, false}), 1);
  EXPECT_EQ(exit_code({Status::Pass, Status::Warn}, {false, true}), 0) << "an expected WARN is no warning of the run";
  for (Status s : {Status::Fail, Status::XPass, Status::Error})
    EXPECT_EQ(exit_code({Status::Warn, s}, {false, false}), 2) << to_string(s) << " outranks a warning";
}

TEST(Status, AnExpectedWarningNotSeenIsSaid) {
  scene::Expectation warn;
  warn.warn = true;
  warn.why = "one map over a kilometre";
  EXPECT_NE(unmet_expectation(warn, Status::Pass), "");
  EXPECT_EQ(unmet_expectation(warn, Status::Warn), "");
  EXPECT_EQ(unmet_expectation(scene::Expectation{}, Status::Pass), "") << "nothing expected, nothing unmet";
}

TEST(Status, PredictedErrorsGrantOnlyWhenTheOtherKindPasses) {
  compare::FolderComparison c;
  c.threshold = &compare::kShadowMap;
  c.masks = {"mask.png"};
  c.per_light.resize(1);
  compare::MaskMetrics& m = c.per_light[0].metrics;
  const auto judged = [&](scene::PredictedErrors predicted, std::string& seen) {
    c.total = m;
    return unpredicted_errors(c, predicted, seen);
  };
  m.edge_pixels = 1000;
  m.unexplained = 100;
  m.unexplained_false_light = 100;  // every unexplained pixel is false light
  std::string seen;
  EXPECT_EQ(judged(scene::PredictedErrors::TooLight, seen), "");
  EXPECT_NE(seen.find("100 mask px"), std::string::npos) << seen;
  EXPECT_NE(judged(scene::PredictedErrors::TooDark, seen), "") << "100 px too light is 10 % of the edges";
  m.unexplained_false_light = 95;  // 5 px false shadow: 0.5 % of the edges, no core
  EXPECT_EQ(judged(scene::PredictedErrors::TooLight, seen), "");
  m.unexplained_false_light = 50;  // 50 px false shadow: 5 %
  EXPECT_NE(judged(scene::PredictedErrors::TooLight, seen), "");
}

// Several lights: the other kind is judged per light, as the verdict is (compare::decide_lights).
// 40 px of false shadow are 4 % of light 1's 1000 edge pixels, though 0.36 % of both lights' 11 000.
TEST(Status, PredictedErrorsOfEachLightAlone) {
  compare::FolderComparison c;
  c.threshold = &compare::kShadowMap;
  c.masks = {"mask_0.png", "mask_1.png"};
  c.per_light.resize(2);
  c.per_light[0].metrics.edge_pixels = 10000;
  compare::MaskMetrics& m = c.per_light[1].metrics;
  m.edge_pixels = 1000;
  m.unexplained = 40;  // all false shadow
  c.total = c.per_light[0].metrics;
  c.total += m;
  std::string seen;
  const std::string problem = unpredicted_errors(c, scene::PredictedErrors::TooLight, seen);
  EXPECT_EQ(problem.rfind("mask_1.png: 40 px too dark", 0), 0u) << problem;
  EXPECT_EQ(unpredicted_errors(c, scene::PredictedErrors::TooDark, seen), "");
}

}  // namespace
}  // namespace shadowref::conform
