// stall_watch_test.cpp — a step that outlasts the watch's interval is reported with its name, and a
// watch ended mid-step says nothing.
#include "stall_watch.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

namespace shadowref::conform {
namespace {

struct Heard {
  std::mutex m;
  std::condition_variable cv;
  std::vector<std::string> lines;
  StallWatch::Report report() {
    return [this](const std::string& line) {
      std::lock_guard<std::mutex> lock(m);
      lines.push_back(line);
      cv.notify_all();
    };
  }
};

TEST(StallWatch, AStepLongerThanTheIntervalIsReportedByName) {
  Heard heard;
  StallWatch watch(heard.report(), std::chrono::seconds(1));
  watch.step("drawing sun_horizon x pcss");
  std::unique_lock<std::mutex> lock(heard.m);
  // A hang guard, not a timing check: the report is due after 1 s.
  ASSERT_TRUE(heard.cv.wait_for(lock, std::chrono::seconds(120), [&] { return !heard.lines.empty(); }));
  EXPECT_EQ(heard.lines.front().rfind("still drawing sun_horizon x pcss after ", 0), 0u) << heard.lines.front();
}

// The interval the tests of a run's stages use (SHADOWREF_STALL_REPORT_MS): each report names the
// step current when it is made, so a new step's name follows at once.
TEST(StallWatch, ASubSecondIntervalReportsTheCurrentStep) {
  Heard heard;
  StallWatch watch(heard.report(), std::chrono::milliseconds(20));
  watch.step("drawing level x pcss");
  std::unique_lock<std::mutex> lock(heard.m);
  ASSERT_TRUE(heard.cv.wait_for(lock, std::chrono::seconds(120), [&] { return !heard.lines.empty(); }));
  lock.unlock();
  watch.step("judging level x pcss");
  lock.lock();
  const auto judging = [&] {
    return !heard.lines.empty() && heard.lines.back().rfind("still judging level x pcss after ", 0) == 0;
  };
  ASSERT_TRUE(heard.cv.wait_for(lock, std::chrono::seconds(120), judging)) << heard.lines.back();
  EXPECT_EQ(heard.lines.front().rfind("still drawing level x pcss after ", 0), 0u) << heard.lines.front();
}

TEST(StallWatch, AWatchEndedMidStepSaysNothing) {
  Heard heard;
  {
    StallWatch watch(heard.report(), std::chrono::seconds(3600));
    watch.step("judging a case");
    watch.step("judging the next case");
  }  // joins at once: the first report would be due in an hour
  EXPECT_TRUE(heard.lines.empty());
}

}  // namespace
}  // namespace shadowref::conform
