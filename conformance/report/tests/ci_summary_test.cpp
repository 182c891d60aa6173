// ci_summary_test.cpp — the JUnit XML and Markdown summary of a conformance run (ci_summary.hpp),
// on a synthetic report.json: every status lands where a CI reader looks for it.
#include <gtest/gtest.h>

#include "shadowref/report/ci_summary.hpp"

namespace shadowref::report {
namespace {

nlohmann::json sample() {
  using nlohmann::json;
  json r;
  r["convention"] = "gl";
  r["plan"] = json::object();  // every report has one (the summaries read a run through its record)
  r["cases"] = json::array();
  r["cases"].push_back({{"scene", "ground_sphere"}, {"technique", "shadowmap"}, {"status", "PASS"}, {"seconds", 0.5}});
  r["cases"].push_back({{"scene", "ground_sphere"}, {"technique", "planar"}, {"status", "FAIL"},
                        {"comparison", {{"total", {{"wrong", 3}, {"unexplained", 3}}}, {"reasons", {"1 unexplained core pixel(s) <here>"}}}}});
  r["cases"].push_back({{"scene", "cornell_box"}, {"technique", "planar"}, {"status", "XFAIL"}, {"why", "walls & ceiling"}});
  r["cases"].push_back({{"scene", "cornell_box"}, {"technique", "shadowmap"}, {"status", "ERROR"}, {"error", "no mask.png"}});
  return r;
}

TEST(CiSummary, JUnitCountsFailuresAndErrorsAndEscapes) {
  const std::string x = render_junit(sample());
  EXPECT_NE(x.find("tests=\"4\" failures=\"1\" errors=\"1\""), std::string::npos) << x;
  EXPECT_NE(x.find("<testcase classname=\"ground_sphere\" name=\"planar\""), std::string::npos) << x;
  EXPECT_NE(x.find("<failure message=\"FAIL: 1 unexplained core pixel(s) &lt;here&gt;\""), std::string::npos) << x;
  EXPECT_NE(x.find("<error message=\"no mask.png\"/>"), std::string::npos) << x;
  EXPECT_NE(x.find("XFAIL: walls &amp; ceiling"), std::string::npos) << x;
}

TEST(CiSummary, MarkdownHasTheCountsTheTableAndTheProblems) {
  const std::string m = render_markdown(sample());
  EXPECT_NE(m.find("4 cases: 1 PASS, 1 XFAIL, 0 WARN, 1 FAIL, 0 XPASS, 1 ERROR (convention gl)"), std::string::npos) << m;
  EXPECT_NE(m.find("| scene | shadowmap | planar |"), std::string::npos) << m;
  EXPECT_NE(m.find("| ground_sphere | PASS | **FAIL** |"), std::string::npos) << m;
  EXPECT_NE(m.find("- **FAIL** ground_sphere × planar: 1 unexplained core pixel(s) <here>"), std::string::npos) << m;
  EXPECT_NE(m.find("- **XFAIL** cornell_box × planar: expected to fail: walls & ceiling"), std::string::npos) << m;
}

// With an engine team's expectations files: a known failure is skipped, not failed; a new failure
// says so; an improvement passes with a note to remove its line; the summary counts each and names
// the stale lines.
TEST(CiSummary, ExpectationsOutcomes) {
  using nlohmann::json;
  json r = sample();
  r["cases"][1]["expectation"] = {{"outcome", "new-failure"}};
  r["cases"][3]["expectation"] = {{"outcome", "expected"}, {"status", "ERROR"}, {"line", "fails.txt:4"}};
  r["cases"][0]["expectation"] = {{"outcome", "improvement"}, {"status", "FAIL"}, {"line", "fails.txt:2"}};
  r["expectations"] = {{"counts", {{"expected", 1}, {"new-failure", 1}, {"improvement", 1}}},
                       {"stale", {{{"line", "fails.txt:9"}, {"text", "gone@planar,FAIL"}}}},
                       {"update", "expectations-update.txt"}};
  r["shard"] = {{"index", 2}, {"total", 3}, {"source", "--shard"}};
  const std::string x = render_junit(r);
  EXPECT_NE(x.find("failures=\"1\" errors=\"0\" skipped=\"1\""), std::string::npos) << x;
  EXPECT_NE(x.find("<failure message=\"new failure: FAIL"), std::string::npos) << x;
  EXPECT_NE(x.find("<skipped message=\"known failure: ERROR at fails.txt:4"), std::string::npos) << x;
  EXPECT_NE(x.find("improvement: PASS where the expectations say FAIL at fails.txt:2: remove that line"), std::string::npos) << x;
  const std::string m = render_markdown(r);
  EXPECT_NE(m.find("| ground_sphere | PASS (improvement) | **FAIL** (new-failure) |"), std::string::npos) << m;
  EXPECT_NE(m.find("ERROR (expected) |"), std::string::npos) << m;  // not in bold: not a failure of the run
  EXPECT_NE(m.find("- **stale** fails.txt:9: `gone@planar,FAIL`"), std::string::npos) << m;
  EXPECT_NE(m.find("1 expected, 1 improvement, 1 new-failure, 1 stale line(s); the next file: `expectations-update.txt`"),
            std::string::npos) << m;
  EXPECT_NE(m.find("Shard 2/3 (--shard)"), std::string::npos) << m;
}

}  // namespace
}  // namespace shadowref::report
