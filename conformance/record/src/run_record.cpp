// run_record.cpp — a whole report.json read into its record (run_record.hpp).
#include "shadowref/record/run_record.hpp"

#include <cstdint>

#include "read_json.hpp"

namespace shadowref::record {
namespace {

using nlohmann::json;
using detail::text_at;

// The object at j[key] (at `where`); an empty object when absent.
const json& object_at(const json& j, const char* key, const std::string& where) {
  static const json none = json::object();
  const auto it = j.find(key);
  if (it == j.end()) return none;
  if (!it->is_object()) throw RecordError(detail::path_at(where, key) + ": must be an object, not " + it->dump());
  return *it;
}

ControlRecord read_control(const json& c, const std::string& where) {
  for (const char* k : {key::kScene, key::kTechnique, key::kStatus})
    if (!c.contains(k)) throw RecordError(detail::path_at(where, k) + ": missing");
  return {text_at(c, key::kScene, where), text_at(c, key::kTechnique, where), detail::status_at(c, key::kStatus, where)};
}

PlanRecord read_plan(const json& report) {
  const json& p = report[key::kPlan];
  PlanRecord plan;
  plan.whole = p;
  if (p.contains(key::kShards)) plan.shards = detail::whole_at(p, key::kShards, key::kPlan, 1);
  plan.techniques = detail::texts_at(p, key::kTechniques, key::kPlan);
  if (const auto scenes = p.find(key::kScenes); scenes != p.end()) {
    if (!scenes->is_array()) throw RecordError(std::string("plan.scenes: must be an array, not ") + scenes->dump());
    for (std::size_t i = 0; i < scenes->size(); ++i) {
      const json& s = (*scenes)[i];
      const std::string at = "plan.scenes[" + std::to_string(i) + "]";
      if (!s.is_object()) throw RecordError(at + ": must be an object, not " + s.dump());
      PlannedScene planned{text_at(s, key::kScene, at), 0};
      if (s.contains(key::kShard)) planned.shard = detail::whole_at(s, key::kShard, at, 1);
      plan.scenes.push_back(std::move(planned));
    }
  }
  return plan;
}

std::optional<ShardRecord> read_shard(const json& report) {
  const auto it = report.find(key::kShard);
  if (it == report.end() || !it->is_object()) return std::nullopt;
  const json& s = *it;
  ShardRecord shard;
  shard.whole = s;
  if (s.contains(key::kIndex)) shard.index = detail::whole_at(s, key::kIndex, key::kShard, 1);
  if (s.contains(key::kTotalShards)) shard.total = detail::whole_at(s, key::kTotalShards, key::kShard, 1);
  shard.source = text_at(s, key::kSource, key::kShard);
  const json& control = object_at(s, key::kControl, key::kShard);
  if (!control.empty()) shard.control = read_control(control, "shard.control");
  return shard;
}

// j[key] (at `where`) as an array of objects, each handed to `one` with its path; none when absent.
template <class One>
void each_object(const json& j, const char* key, const std::string& where, One one) {
  const auto it = j.find(key);
  if (it == j.end()) return;
  const std::string at = detail::path_at(where, key);
  if (!it->is_array()) throw RecordError(at + ": must be an array, not " + it->dump());
  for (std::size_t i = 0; i < it->size(); ++i) {
    const std::string item = at + "[" + std::to_string(i) + "]";
    if (!(*it)[i].is_object()) throw RecordError(item + ": must be an object, not " + (*it)[i].dump());
    one((*it)[i], item);
  }
}

std::vector<ThresholdRecord> read_thresholds(const json& report) {
  std::vector<ThresholdRecord> out;
  each_object(report, key::kThresholds, "", [&](const json& t, const std::string& at) {
    ThresholdRecord r;
    r.name = text_at(t, key::kName, at);
    r.why = text_at(t, key::kWhy, at);
    if (const auto b = t.find(key::kBands); b != t.end()) {
      if (!b->is_boolean()) throw RecordError(detail::path_at(at, key::kBands) + ": must be true or false, not " + b->dump());
      r.bands = b->get<bool>();
    }
    r.unexplained_fail_percent = detail::number_at(t, key::kUnexplainedFailPercent, at);
    r.explained_warn_percent = detail::number_at(t, key::kExplainedWarnPercent, at);
    out.push_back(std::move(r));
  });
  return out;
}

std::optional<ExpectationsRecord> read_expectations(const json& report) {
  const json& e = object_at(report, key::kExpectations, "");
  if (!report.contains(key::kExpectations)) return std::nullopt;
  ExpectationsRecord r;
  r.files = detail::texts_at(e, key::kFiles, key::kExpectations);
  for (const auto& [outcome, n] : object_at(e, key::kCounts, key::kExpectations).items()) {
    if (!n.is_number_integer() || n.get<std::int64_t>() < 0)
      throw RecordError(std::string("expectations.counts.") + outcome + ": must be a whole number >= 0, not " + n.dump());
    r.counts.emplace_back(outcome, n.get<std::size_t>());
  }
  each_object(e, key::kStale, key::kExpectations, [&](const json& s, const std::string& at) {
    r.stale.push_back({text_at(s, key::kLine, at), text_at(s, key::kText, at)});
  });
  r.update = text_at(e, key::kUpdate, key::kExpectations);
  return r;
}

TriageRecord read_triage(const json& report) {
  const json& t = object_at(report, key::kTriage, "");
  TriageRecord r{text_at(t, key::kBase, key::kTriage), {}};
  each_object(t, key::kCases, key::kTriage, [&](const json& c, const std::string& at) {
    r.cases.push_back({text_at(c, key::kScene, at), text_at(c, key::kTechnique, at), text_at(c, key::kLine, at)});
  });
  return r;
}

// The page's header: the tool, when, and how the run drew.
void read_about(const json& report, RunRecord& r) {
  const auto optional_text = [&](const json& j, const char* k, const std::string& where) {
    return j.contains(k) && !j[k].is_null() ? std::optional<std::string>(text_at(j, k, where)) : std::nullopt;
  };
  r.tool = text_at(report, key::kTool, "");
  r.version = text_at(report, key::kVersion, "");
  r.generated = text_at(report, key::kGenerated, "");
  r.mode = text_at(report, key::kMode, "");
  r.candidate_dir = optional_text(report, key::kCandidateDir, "");
  r.backend = optional_text(report, key::kBackend, "");
  r.gl_api = optional_text(report, key::kGlApi, "");
  const json& gl = object_at(report, key::kGl, "");
  r.gl_renderer = optional_text(gl, key::kRenderer, key::kGl);
  r.gl_version = optional_text(gl, key::kVersion, key::kGl);
  const json& reference = object_at(report, key::kReference, "");
  if (reference.contains(key::kSamplesPerAxis)) r.samples_per_axis = detail::whole_at(reference, key::kSamplesPerAxis, key::kReference, 1);
}

}  // namespace

RunRecord read_run(const json& report) {
  if (!report.is_object()) throw RecordError("the report: must be an object");
  if (!report.contains(key::kPlan) || !report[key::kPlan].is_object()) throw RecordError("plan: missing or not an object");
  if (!report.contains(key::kCases) || !report[key::kCases].is_array()) throw RecordError("cases: missing or not an array");
  RunRecord r;
  read_about(report, r);
  r.convention = text_at(report, key::kConvention, "");
  if (report.contains(key::kHost)) r.host = text_at(report, key::kHost, "");
  if (const auto s = report.find(key::kSeconds); s != report.end()) {
    if (!s->is_number() || !(s->get<double>() >= 0)) throw RecordError("seconds: must be a number >= 0, not " + s->dump());
    r.seconds = s->get<double>();
  }
  r.plan = read_plan(report);
  r.shard = read_shard(report);
  r.skipped = detail::texts_at(report, key::kSkipped, "");
  r.scenes = detail::texts_at(report, key::kScenes, "");
  r.techniques = detail::texts_at(report, key::kTechniques, "");
  r.thresholds = read_thresholds(report);
  r.expectations = read_expectations(report);
  r.triage = read_triage(report);
  r.catalogue = r.plan.whole.value(key::kCatalogue, json());
  r.declarations = report.value(key::kDeclarations, json());
  r.cases = read_cases(report);
  return r;
}

std::vector<std::string> case_images(const CaseRecord& c) {
  std::vector<std::string> out;
  const auto add = [&](const std::string& rel) {
    if (!rel.empty()) out.push_back(rel);
  };
  add(c.shaded);
  add(c.reference_shaded);
  for (const LightRecord& l : c.lights)
    for (const std::string* rel : {&l.reference, &l.decided, &l.candidate, &l.error, &l.candidate_visibility, &l.visibility_error})
      add(*rel);
  return out;
}

}  // namespace shadowref::record
