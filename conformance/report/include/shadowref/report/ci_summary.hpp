// shadowref/report/ci_summary.hpp — what a CI system reads of a conformance run, made from the data
// of report.json alone (like the HTML page):
//   * JUnit XML: one <testcase classname="<scene>" name="<technique>"> per case; FAIL and XPASS are
//     <failure> with the verdict's reasons, ERROR is <error>, PASS / XFAIL / WARN pass (XFAIL and
//     WARN say so in <system-out>), the format Jenkins, GitLab and GitHub test reporters read;
//   * Markdown: the counts, the scene × technique table, and one line per case that is not PASS
//     with its why and reasons — suitable for a CI step summary ($GITHUB_STEP_SUMMARY).
// Both carry each case's resolving power (tolerance/resolving_power.hpp): a JUnit <property
// name="resolving_power">, and in the Markdown the count of blind cases with how to sharpen them.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include <vector>

#include <nlohmann/json.hpp>

#include "shadowref/record/case_record.hpp"

namespace shadowref::report {

// The cases of a report whose resolving power is blind to a probe, of those judged with one, and the
// blind kinds with their counts ("1-px shifts: 3, 8x8 tiles: 1").
struct BlindCases {
  std::size_t judged = 0, blind = 0;
  std::string kinds;
};
BlindCases blind_cases(const std::vector<record::CaseRecord>& cases);

// What a team does about a blind case (the summaries and the HTML say it).
inline constexpr const char* kHowToSharpen =
    "render the pack at --resolution-scale 2 (a texel of a given map then spans more pixels less often), declare a "
    "larger map or a smaller filter where the engine draws one, or give the light matrices (\"light_views\": "
    "\"pack\" when the engine uses the pack's)";

std::string render_junit(const nlohmann::json& report);
std::string render_markdown(const nlohmann::json& report);

// Write them to `file` (creating its folder). Throw std::runtime_error naming the file.
void write_junit(const nlohmann::json& report, const std::filesystem::path& file);
void write_markdown(const nlohmann::json& report, const std::filesystem::path& file);

}  // namespace shadowref::report
