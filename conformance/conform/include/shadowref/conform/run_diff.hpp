// shadowref/conform/run_diff.hpp — one finished run against another (`shadowref diff RUN_A RUN_B`):
// which cases changed between them, and where their candidate masks differ.
//
// The runs are two `conform` or `merge` --out folders (run_report.hpp), e.g. yesterday's and today's,
// or one engine's WebGL2 and WebGPU renders judged each as a run. A case is scene@technique (the
// runs may be in other conventions: a note, not a refusal). A case present in both changed when its
// status, its wrong or unexplained pixel count (all lights, report.json's comparison.total) or any
// byte of its candidate masks (the copies in each run's report/) differs, or when the two cannot be
// compared mask for mask (other mask names or sizes, masks in one run only); a case present in one
// run only changed too. Masks are compared byte for byte on every pixel, decided or not: the
// question is where two renders differ, not which one is right.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowref::conform {

// One light of a case as a run's report.json shows it: its mask name and the report's copies of the
// candidate mask and the error image (absolute; empty when the run has none, a case in ERROR).
struct DiffLight {
  std::string mask;
  std::filesystem::path candidate, error;
};

// One run's side of a case.
struct DiffSide {
  std::string status;                              // "PASS", "FAIL", ...
  std::optional<std::size_t> wrong, unexplained;   // none for a case that ended before a verdict
  std::vector<DiffLight> lights;
};

// The candidate masks of a case present in both runs, compared light by light.
struct MaskComparison {
  std::vector<std::size_t> differ;      // per light: pixels whose bytes differ
  std::size_t differ_total = 0, pixels_total = 0;
  std::string not_compared;             // why the masks could not be compared; "" when they were
  bool not_compared_is_change = false;  // masks in one run only, other names or sizes (not: in neither)
};

struct CaseDiff {
  std::string scene, technique;
  std::optional<DiffSide> a, b;
  MaskComparison masks;               // cases in both runs only
  std::vector<std::string> changes;   // what changed, one phrase each ("status PASS -> FAIL"); empty: nothing
  bool changed() const { return !changes.empty(); }
};

struct RunDiff {
  std::filesystem::path a, b;
  std::string convention_a, convention_b;
  std::vector<CaseDiff> cases;  // every case of either run: A's order, then those of B only
  std::size_t changed() const;
  std::size_t only_in_a() const;
  std::size_t only_in_b() const;
};

// Reads both runs and compares them. Throws ReportUnreadable (run_report.hpp) naming the file and
// the JSON path of what is wrong (a missing report.json, a case without a scene, a case twice, an
// image path that leaves the report folder), outputs::InputError naming a mask that cannot be read.
RunDiff diff_runs(const std::filesystem::path& a, const std::filesystem::path& b);

// The diff as JSON: the runs, the counts and every changed case (what `diff --json` prints and the
// page is made from). Image paths are not in it: the page's writer adds its own copies' paths.
nlohmann::json to_json(const RunDiff& d);

// One line per changed case, for the terminal ("changed  ground_sphere@shadowmap: status PASS -> FAIL; ...").
std::string case_line(const CaseDiff& c);

}  // namespace shadowref::conform
