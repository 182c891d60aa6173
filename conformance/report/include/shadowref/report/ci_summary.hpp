// shadowref/report/ci_summary.hpp — what a CI system reads of a conformance run, made from the data
// of report.json alone (like the HTML page):
//   * JUnit XML: one <testcase classname="<scene>" name="<technique>"> per case; FAIL and XPASS are
//     <failure> with the verdict's reasons, ERROR is <error>, PASS / XFAIL / WARN pass (XFAIL and
//     WARN say so in <system-out>), the format Jenkins, GitLab and GitHub test reporters read;
//   * Markdown: the counts, the scene × technique table, and one line per case that is not PASS
//     with its why and reasons — suitable for a CI step summary ($GITHUB_STEP_SUMMARY).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace shadowref::report {

std::string render_junit(const nlohmann::json& report);
std::string render_markdown(const nlohmann::json& report);

// Write them to `file` (creating its folder). Throw std::runtime_error naming the file.
void write_junit(const nlohmann::json& report, const std::filesystem::path& file);
void write_markdown(const nlohmann::json& report, const std::filesystem::path& file);

}  // namespace shadowref::report
