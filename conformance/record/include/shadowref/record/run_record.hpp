// shadowref/record/run_record.hpp — a whole report.json as one typed record: the run-level keys a
// reader acts on (its plan, its shard, its skipped cases, where it ran) beside its cases' records.
//
// What `merge` checks shards by and joins them with, and what every other reader of a run needs
// besides its cases. The keys that a reader only compares whole (the catalogue's identity, the run's
// declarations, the plan's weights) travel as JSON in `whole`, read by no one key by key. The
// record's reader is strict in the way read_case is: a key that is there must have its type, and a
// shard number is a whole number from 1 to INT_MAX, never a float cast out of range.
#pragma once

#include <optional>
#include <string>
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
  std::optional<ControlRecord> control;  // none only when a [skips] pattern left it out
  nlohmann::json whole;                  // "shard" as written, kept in a merged report's provenance
};

struct RunRecord {
  std::string version, convention;
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
// 2147483647, not 1e+300"). Cost: read_cases plus one pass over the plan.
RunRecord read_run(const nlohmann::json& report);

// Every image a case shows, as paths relative to report/ that stay in it (read_case checked them):
// its shaded views and, for each light, its reference, decided, candidate and error images and
// their lit-fraction twins. What a reader copies when it moves a case to another report.
std::vector<std::string> case_images(const CaseRecord& c);

}  // namespace shadowref::record
