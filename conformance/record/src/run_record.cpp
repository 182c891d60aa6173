// run_record.cpp — a whole report.json read into its record (run_record.hpp).
#include "shadowref/record/run_record.hpp"

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
  const json& control = object_at(s, key::kControl, key::kShard);
  if (!control.empty()) shard.control = read_control(control, "shard.control");
  return shard;
}

}  // namespace

RunRecord read_run(const json& report) {
  if (!report.is_object()) throw RecordError("the report: must be an object");
  if (!report.contains(key::kPlan) || !report[key::kPlan].is_object()) throw RecordError("plan: missing or not an object");
  if (!report.contains(key::kCases) || !report[key::kCases].is_array()) throw RecordError("cases: missing or not an array");
  RunRecord r;
  r.version = text_at(report, key::kVersion, "");
  r.convention = text_at(report, key::kConvention, "");
  if (report.contains(key::kHost)) r.host = text_at(report, key::kHost, "");
  if (const auto s = report.find(key::kSeconds); s != report.end()) {
    if (!s->is_number() || !(s->get<double>() >= 0)) throw RecordError("seconds: must be a number >= 0, not " + s->dump());
    r.seconds = s->get<double>();
  }
  r.plan = read_plan(report);
  r.shard = read_shard(report);
  r.skipped = detail::texts_at(report, key::kSkipped, "");
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
