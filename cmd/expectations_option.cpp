// expectations_option.cpp — `--expectations FILE` (repeatable), the same in `conform`, `compare`
// and `merge`, and what the terminal shows of a run against those files (docs/ci.md).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <stdexcept>

#include "command.hpp"
#include "shadowref/conform/conform.hpp"
#include "shadowref/ci/expectations.hpp"

namespace shadowref::cli {

void add_expectations_option(CLI::App& cmd, std::vector<std::string>& files) {
  cmd.add_option("--expectations", files,
                 "an engine team's known failures (repeatable): lines 'scene@technique[@convention],STATUS' (WARN, FAIL, "
                 "XPASS, ERROR), '#' comments, [flakes] and [skips] sections of regexes over 'scene@technique@convention'. "
                 "A case as expected is no failure; a new failure exits 2, an improvement 1; the next file is written as "
                 "OUT/expectations-update.txt (docs/ci.md)")
      // One file per --expectations, so that `merge --expectations F DIR...` does not read the shards as files.
      ->allow_extra_args(false);
}

ci::Expectations read_expectations_option(const std::vector<std::string>& files) {
  std::vector<std::filesystem::path> paths(files.begin(), files.end());
  try {
    return ci::read_expectations(paths);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("--expectations ") + e.what());
  }
}

void print_expectation_lines(const conform::ConformResult& r, const ci::Expectations& e) {
  if (e.empty()) return;
  std::size_t counts[6] = {};
  for (const conform::CaseResult& c : r.cases) {
    ++counts[static_cast<int>(c.outcome)];
    const char* what = c.outcome == conform::Outcome::NewFailure    ? "NEW FAILURE"
                       : c.outcome == conform::Outcome::NewWarning  ? "NEW WARNING"
                       : c.outcome == conform::Outcome::Improvement ? "IMPROVEMENT"
                                                                    : nullptr;
    if (!what) continue;
    std::printf("%-11s %s: %s", what, ci::case_name(c.scene, c.technique, r.convention).c_str(), conform::to_string(c.status));
    if (c.expected_line.empty()) std::printf(", not in the expectations files\n");
    else if (c.outcome == conform::Outcome::Improvement)
      std::printf(" where %s expects %s: remove that line\n", c.expected_line.c_str(), c.expected_status.c_str());
    else std::printf(" where %s expects %s\n", c.expected_line.c_str(), c.expected_status.c_str());
  }
  for (const ci::ExpectationLine* l : r.stale)
    std::printf("STALE       %s: '%s' names no case of this run\n", l->where.c_str(), l->text.c_str());
  for (const std::string& s : r.skipped) std::printf("SKIP        %s: a [skips] regex\n", s.c_str());
  using conform::Outcome;
  std::printf("against the expectations files: %zu known, %zu new failure(s), %zu new warning(s), %zu improvement(s), "
              "%zu flaky, %zu stale line(s), %zu skipped; the next file: %s\n",
              counts[static_cast<int>(Outcome::Expected)], counts[static_cast<int>(Outcome::NewFailure)],
              counts[static_cast<int>(Outcome::NewWarning)], counts[static_cast<int>(Outcome::Improvement)],
              counts[static_cast<int>(Outcome::Flake)], r.stale.size(), r.skipped.size(),
              (r.report_json.parent_path() / "expectations-update.txt").string().c_str());
}

}  // namespace shadowref::cli
