// shadowref/record/run_record.hpp — a whole report.json as one typed record: the run-level keys a
// reader acts on (its plan, its shard, its skipped cases, where and how it ran, its thresholds, what
// its expectations files came to, its triage) beside its cases' records.
//
// What `merge` checks shards by and joins them with, what the page, JUnit and summary.md show of a
// run, and what every other reader of a run needs besides its cases. The keys that a reader only compares whole (the catalogue's identity, the run's
// declarations, the plan's weights) travel as JSON in `whole`, read by no one key by key. The
// record's reader is strict in the way read_case is: a key that is there must have its type, and a
// shard number is a whole number from 1 to INT_MAX, never a float cast out of range.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowref/record/case_record.hpp"

namespace shadowref::record {

// The run-level keys (report.json's top level, "plan" and "shard"; docs/output-contract.md).
namespace key {
inline constexpr char kVersion[] = "version";
inline constexpr char kConvention[] = "convention";
inline constexpr char kPlan[] = "plan";
inline constexpr char kSkipped[] = "skipped";
inline constexpr char kDeclarations[] = "declarations";
// Inside "plan": its scenes (each {"scene", "shard"}), techniques, shard count and catalogue.
inline constexpr char kScenes[] = "scenes";
inline constexpr char kTechniques[] = "techniques";
inline constexpr char kShards[] = "shards";
inline constexpr char kCatalogue[] = "catalogue";
inline constexpr char kControl[] = "control";  // also "shard"."control": {"scene", "technique", "status"}
// Inside "shard" (kShard): this shard's number of the run's total.
inline constexpr char kIndex[] = "index";
inline constexpr char kTotalShards[] = "total";
inline constexpr char kSource[] = "source";  // where the shard's numbers came from ("--shard", "GTEST_SHARD_INDEX")
// What the page's header says of the run: its tool, when, how it drew ("gl" holds the driver's
// "renderer" and "version") and the reference's sampling ("reference"."samples_per_axis").
inline constexpr char kTool[] = "tool";
inline constexpr char kGenerated[] = "generated";
inline constexpr char kMode[] = "mode";  // "render" or "candidate-dir" (a run's kCandidateDir says which folder)
inline constexpr char kBackend[] = "backend";
inline constexpr char kGlApi[] = "gl_api";
inline constexpr char kGl[] = "gl";
inline constexpr char kRenderer[] = "renderer";
inline constexpr char kSamplesPerAxis[] = "samples_per_axis";
// "thresholds": each threshold of the comparison (report/comparison_json.hpp writes them).
inline constexpr char kThresholds[] = "thresholds";
inline constexpr char kName[] = "name";
inline constexpr char kBands[] = "bands";
inline constexpr char kUnexplainedFailPercent[] = "unexplained_fail_percent_of_edges";
inline constexpr char kExplainedWarnPercent[] = "explained_warn_percent_of_edges";
// "expectations": the files a run was given, each outcome's count, the stale lines (each a kLine and
// its kText) and the next file's name.
inline constexpr char kExpectations[] = "expectations";
inline constexpr char kFiles[] = "files";
inline constexpr char kCounts[] = "counts";
inline constexpr char kStale[] = "stale";
inline constexpr char kText[] = "text";
inline constexpr char kUpdate[] = "update";
// "triage": the file the run was given without its new lines (kBase), and each new case's line
// ({kScene, kTechnique, kLine}, in "cases").
inline constexpr char kTriage[] = "triage";
inline constexpr char kBase[] = "base";
}  // namespace key

// A scene of the plan and the shard that judges it (1-based; 0 when the plan names none).
struct PlannedScene {
  std::string scene;
  int shard = 0;
};

// What a run set out to judge: the same for every shard of one run.
struct PlanRecord {
  std::vector<PlannedScene> scenes;
  std::vector<std::string> techniques;
  int shards = 1;
  nlohmann::json whole;  // the plan as written (its weights, assignment and control besides), compared whole
};

// The control case every shard of a run judges (the merge checks that they agree).
struct ControlRecord {
  std::string scene, technique;
  Status status = Status::Pass;
};

// A shard's place in its run: shard `index` of `total` (1-based; 0 when "shard" does not say).
struct ShardRecord {
  int index = 0, total = 0;
  std::string source;                    // which flag or variable gave the numbers
  std::optional<ControlRecord> control;  // none only when a [skips] pattern left it out
  nlohmann::json whole;                  // "shard" as written, kept in a merged report's provenance
};

// A threshold of the comparison as the page lists it (compare/thresholds.hpp says what each means).
struct ThresholdRecord {
  std::string name, why;
  bool bands = false;  // whether the texel and bias bands explain pixels under it
  std::optional<double> unexplained_fail_percent, explained_warn_percent;  // of the edge pixels
};

// An expectations line that names no case of the run.
struct StaleLineRecord {
  std::string line, text;  // its place ("fails.txt:9") and its text
};

// What the expectations files a run was given came to (present only when it was given any).
struct ExpectationsRecord {
  std::vector<std::string> files;
  std::vector<std::pair<std::string, std::size_t>> counts;  // each outcome's name and count, in the file's order
  std::vector<StaleLineRecord> stale;
  std::string update;  // the next file's name, beside report.json
};

// A new failure or warning of the run, with the line that would make it known.
struct TriageLineRecord {
  std::string scene, technique, line;
};

// What the page's triage needs: the file the run was given without its new lines, and each new case.
struct TriageRecord {
  std::string base;
  std::vector<TriageLineRecord> cases;
};

struct RunRecord {
  std::string tool, version, generated, convention;
  std::string mode;                                          // "render" or "candidate-dir"
  std::optional<std::string> candidate_dir, backend, gl_api;  // a candidate-dir run has the first only
  std::optional<std::string> gl_renderer, gl_version;        // the driver that drew ("gl")
  std::optional<int> samples_per_axis;                       // the reference's, per pixel and axis
  std::vector<std::string> scenes, techniques;               // what the run judged, in its order
  std::vector<ThresholdRecord> thresholds;
  std::optional<ExpectationsRecord> expectations;
  TriageRecord triage;
  std::optional<std::string> host;  // the machine that ran it (a merged report has none)
  double seconds = 0;               // the run's wall time
  PlanRecord plan;
  std::optional<ShardRecord> shard;  // present in a shard of a split run
  std::vector<std::string> skipped;  // the cases a [skips] pattern left out, by name
  nlohmann::json catalogue, declarations;  // compared whole: the same run's shards share them
  std::vector<CaseRecord> cases;
};

// The record of `report`, which must be an object with "plan" (an object) and "cases" (an array).
// Throws RecordError naming the JSON path ("plan.shards: must be a whole number from 1 to
// 2147483647, not 1e+300"). Cost: read_cases plus one pass over the plan, the thresholds, the
// expectations and the triage.
RunRecord read_run(const nlohmann::json& report);

// Every image a case shows, as paths relative to report/ that stay in it (read_case checked them):
// its shaded views and, for each light, its reference, decided, candidate and error images and
// their lit-fraction twins. What a reader copies when it moves a case to another report.
std::vector<std::string> case_images(const CaseRecord& c);

}  // namespace shadowref::record
