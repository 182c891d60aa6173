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
  c.total.edge_pixels = 1000;
  c.total.unexplained = 100;
  c.total.unexplained_false_light = 100;  // every unexplained pixel is false light
  std::string seen;
  EXPECT_EQ(unpredicted_errors(c, scene::PredictedErrors::TooLight, seen), "");
  EXPECT_NE(seen.find("100 mask px"), std::string::npos) << seen;
  EXPECT_NE(unpredicted_errors(c, scene::PredictedErrors::TooDark, seen), "") << "100 px too light is 10 % of the edges";
  c.total.unexplained_false_light = 95;  // 5 px false shadow: 0.5 % of the edges, no core
  EXPECT_EQ(unpredicted_errors(c, scene::PredictedErrors::TooLight, seen), "");
  c.total.unexplained_false_light = 50;  // 50 px false shadow: 5 %
  EXPECT_NE(unpredicted_errors(c, scene::PredictedErrors::TooLight, seen), "");
}

}  // namespace
}  // namespace shadowref::conform
