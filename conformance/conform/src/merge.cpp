// merge.cpp — the shards of a split run checked to be one complete run and joined into one report
// (merge.hpp).
#include "shadowref/conform/merge.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdint>
#include <ctime>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <system_error>

#include "report_writer.hpp"
#include "shadowref/conform/run_report.hpp"
#include "shadowref/record/case_record.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/staged_folder.hpp"

namespace shadowref::conform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Shard {
  fs::path dir;
  json report;
  int index = 1, total = 1;  // 1-based; an unsplit run is shard 1/1
};

// A shard's report is read as every finished run's (run_report.hpp).
std::string text_of(const json& j, const char* key) { return report_text(j, key); }

// The shard numbers a report holds (plan.shards, each plan.scenes[].shard and scene, shard.index
// and shard.total), each checked once here so that every later reading of them holds: a number must
// be a whole one from 1 to INT_MAX (a float is never cast out of range), a scene a string.
void check_shard_numbers(const json& report, const fs::path& file) {
  const auto refuse = [&](const std::string& path, const json& v, const char* what) {
    throw MergeRefused({file.string() + ": " + path + ": must be " + what + ", not " + v.dump()});
  };
  const auto whole = [&](const json& o, const char* key, const std::string& at) {
    const auto it = o.find(key);
    if (it == o.end()) return;
    const bool ok = it->is_number_integer() && (it->is_number_unsigned() ? it->get<std::uint64_t>() <= INT_MAX
                                                                           : it->get<std::int64_t>() >= 1 &&
                                                                                 it->get<std::int64_t>() <= INT_MAX);
    if (!ok || *it == 0) refuse(at + key, *it, "a whole number from 1 to 2147483647");
  };
  const json& plan = report["plan"];
  whole(plan, "shards", "plan.");
  if (const auto scenes = plan.find("scenes"); scenes != plan.end()) {
    if (!scenes->is_array()) refuse("plan.scenes", *scenes, "an array");
    for (std::size_t i = 0; i < scenes->size(); ++i) {
      const json& p = (*scenes)[i];
      const std::string at = "plan.scenes[" + std::to_string(i) + "]";
      if (!p.is_object()) refuse(at, p, "an object");
      if (p.contains("scene") && !p["scene"].is_string()) refuse(at + ".scene", p["scene"], "a string");
      whole(p, "shard", at + ".");
    }
  }
  if (const auto shard = report.find("shard"); shard != report.end() && shard->is_object()) {
    whole(*shard, "index", "shard.");
    whole(*shard, "total", "shard.");
  }
}

Shard read_shard(const fs::path& dir) {
  Shard s;
  s.dir = dir;
  try {
    s.report = read_run_report(dir);
  } catch (const ReportUnreadable& e) {
    throw MergeRefused({e.what()});
  }
  // Every case through its record once here, so that a case of the wrong shape is refused with its
  // JSON path before anything is merged (and every later reading of a case holds).
  try {
    record::read_cases(s.report);
  } catch (const record::RecordError& e) {
    throw MergeRefused({(dir / "report.json").string() + ": " + e.what()});
  }
  check_shard_numbers(s.report, dir / "report.json");
  if (s.report.contains("shard") && s.report["shard"].is_object()) {
    s.index = s.report["shard"].value("index", 0);
    s.total = s.report["shard"].value("total", 0);
  }
  return s;
}

// The same run: version, catalogue, convention, declarations and plan as the first shard's; each
// shard index once and none missing.
void check_one_run(const std::vector<Shard>& shards, std::vector<std::string>& problems) {
  const Shard& first = shards.front();
  // One line per shard and cause: the first of these that differs says it (another convention
  // also makes another plan, which is not said again).
  const auto text = [](const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); };
  const auto differs = [&](const Shard& s, const std::string& what, const json& a, const json& b) {
    if (a == b) return false;
    if (a.is_object() && b.is_object()) {  // the declarations: only the keys that differ
      std::string mine, theirs;
      for (const auto& [k, v] : a.items())
        if (!b.contains(k) || b[k] != v) {
          mine += (mine.empty() ? "" : ", ") + k + " " + text(v);
          theirs += (theirs.empty() ? "" : ", ") + k + " " + (b.contains(k) ? text(b[k]) : "(none)");
        }
      problems.push_back(s.dir.string() + ": " + what + " " + mine + ", but " + first.dir.string() + " has " + theirs);
      return true;
    }
    problems.push_back(s.dir.string() + ": " + what + " " + text(a) + ", but " + first.dir.string() + " has " + text(b));
    return true;
  };
  for (std::size_t i = 1; i < shards.size(); ++i) {
    const json &r = shards[i].report, &f = first.report;
    if (differs(shards[i], "suite version", r.value("version", json()), f.value("version", json())) ||
        differs(shards[i], "catalogue", r["plan"].value("catalogue", json()), f["plan"].value("catalogue", json())) ||
        differs(shards[i], "convention", r.value("convention", json()), f.value("convention", json())) ||
        differs(shards[i], "declarations", r.value("declarations", json()), f.value("declarations", json())))
      continue;
    if (r["plan"] != f["plan"])
      problems.push_back(shards[i].dir.string() + ": another plan than " + first.dir.string() +
                         "'s (other scenes, techniques, shard count or weights)");
  }
  const int total = first.report["plan"].value("shards", 1);
  std::map<int, const Shard*> seen;
  for (const Shard& s : shards) {
    if (s.total != total) continue;  // a plan of another shard count is said above
    if (const auto it = seen.find(s.index); it != seen.end())
      problems.push_back("shard " + std::to_string(s.index) + "/" + std::to_string(total) + " given twice: " +
                         it->second->dir.string() + " and " + s.dir.string());
    else seen[s.index] = &s;
  }
  for (int k = 1; k <= total; ++k) {
    if (seen.count(k)) continue;
    std::string scenes;
    for (const json& p : first.report["plan"].value("scenes", json::array()))
      if (p.value("shard", 0) == k) scenes += (scenes.empty() ? "" : ", ") + p.value("scene", "");
    problems.push_back("shard " + std::to_string(k) + "/" + std::to_string(total) + " missing (its scenes: " +
                       (scenes.empty() ? "none" : scenes) + ")");
  }
}

// Each planned case once, from the shard the plan gives it; every shard's control case alike.
// Returns the cases in the unsplit run's order (plan scenes × techniques), each with its shard.
std::vector<json> gather_cases(const std::vector<Shard>& shards, std::vector<std::string>& problems) {
  const json& plan = shards.front().report["plan"];
  const std::string convention = text_of(shards.front().report, "convention");
  std::map<std::string, int> planned_shard;
  for (const json& p : plan.value("scenes", json::array())) planned_shard[p.value("scene", "")] = p.value("shard", 0);
  std::map<std::pair<std::string, std::string>, std::pair<json, const Shard*>> at;
  std::set<std::string> skipped, present_shards;
  for (const Shard& s : shards) {
    // A shard given twice is said once (check_one_run), not once more per case.
    if (!present_shards.insert(std::to_string(s.index)).second) continue;
    for (const json& k : s.report.value("skipped", json::array())) skipped.insert(k.get<std::string>());
    for (json c : s.report["cases"]) {
      const std::string scene = text_of(c, "scene"), technique = text_of(c, "technique");
      const std::string name = case_name(scene, technique, convention);
      if (const auto it = at.find({scene, technique}); it != at.end()) {
        problems.push_back("case " + name + " seen twice: in " + it->second.second->dir.string() + " and " + s.dir.string());
        continue;
      }
      if (planned_shard.count(scene) && planned_shard[scene] != s.index && s.total > 1)
        problems.push_back("case " + name + " in " + s.dir.string() + " (shard " + std::to_string(s.index) +
                           "), but the plan gives it to shard " + std::to_string(planned_shard[scene]));
      c["shard"] = s.index;
      if (!c.contains("host")) c["host"] = s.report.value("host", "");
      at[{scene, technique}] = {c, &s};
    }
  }
  std::vector<json> out;
  for (const json& p : plan.value("scenes", json::array()))
    for (const json& t : plan.value("techniques", json::array())) {
      const std::string scene = p.value("scene", ""), technique = t.get<std::string>();
      const auto it = at.find({scene, technique});
      if (it != at.end()) {
        out.push_back(it->second.first);
        continue;
      }
      const std::string name = case_name(scene, technique, convention);
      // A missing shard is said once, above, not once per case.
      if (!skipped.count(name) && present_shards.count(std::to_string(p.value("shard", 0))))
        problems.push_back("case " + name + " missing: planned for shard " + std::to_string(p.value("shard", 0)) +
                           ", which does not have it");
    }
  std::string control_status;
  for (const Shard& s : shards) {
    const json control = s.report.contains("shard") ? s.report["shard"].value("control", json::object()) : json::object();
    if (control.empty()) continue;
    const std::string status = text_of(control, "status");
    if (control_status.empty()) control_status = status;
    else if (status != control_status)
      problems.push_back(s.dir.string() + ": the control case " + text_of(control, "scene") + "@" + text_of(control, "technique") +
                         " is " + status + " there and " + control_status + " in " + shards.front().dir.string() +
                         ": the shards' machines judge differently");
  }
  return out;
}

// Copies every image a case shows from its shard's report/ into the merged one.
void copy_images(const json& c, const fs::path& from_report, const outputs::StagedFolder& staged) {
  std::vector<std::string> rels;
  for (const char* key : {"shaded", "reference_shaded"})
    if (c.contains(key) && c[key].is_string()) rels.push_back(c[key].get<std::string>());
  for (const json& l : c.value("lights", json::array()))
    for (const char* key : {"reference", "decided", "candidate", "error", "candidate_visibility", "visibility_error"})
      if (l.contains(key) && l[key].is_string()) rels.push_back(l[key].get<std::string>());
  for (const std::string& rel : rels) {
    if (rel.empty()) continue;
    if (!inside_report_folder(rel)) throw MergeRefused({from_report.string() + ": image path '" + rel + "' leaves the report folder"});
    std::error_code ec;
    if (fs::exists(staged.path() / rel, ec)) continue;  // a scene's reference images, shared by its cases
    fs::create_directories((staged.path() / rel).parent_path(), ec);
    if (ec) throw outputs::FileError((staged.final_path() / rel).parent_path(), "create the folder", ec.value());
    outputs::copy_file_atomically(from_report / rel, staged.path() / rel);
  }
}

// The merged cases as a ConformResult (table and exit code), each classified against `e`.
ConformResult merged_result(const json& first, std::vector<json>& cases, const Expectations& e) {
  ConformResult r;
  r.convention = text_of(first, "convention");
  for (const json& p : first["plan"].value("scenes", json::array())) r.scenes.push_back(p.value("scene", ""));
  r.techniques = first["plan"].value("techniques", std::vector<std::string>{});
  for (json& c : cases) {
    record::CaseRecord rec = record::read_case(c, r.cases.size());  // its shape was checked by read_shard
    CaseResult k;
    k.scene = rec.scene;
    k.technique = rec.technique;
    k.status = rec.status;
    k.expected.warn = rec.expected == "warn";
    k.environment = rec.environment;  // as the shard wrote it
    const ExpectationLine* line = e.line_for(k.scene, k.technique, r.convention, k.environment);
    k.outcome = outcome_of(k.status, k.expected.warn, line, e.flaky(case_name(k.scene, k.technique, r.convention)));
    c.erase(record::key::kExpectation);
    if (!e.empty()) {
      rec.expectation = record::ExpectationRecord{k.outcome, line ? to_string(line->status) : "", line ? line->where : ""};
      record::write_case(rec, c);
    }
    r.cases.push_back(std::move(k));
  }
  return r;
}

}  // namespace

MergeRefused::MergeRefused(std::vector<std::string> problems)
    : std::invalid_argument(problems.empty() ? "" : problems.front()), problems_(std::move(problems)) {}

ConformResult merge_shards(const MergeOptions& o) {
  if (o.shards.empty()) throw std::invalid_argument("no shard folders given");
  std::vector<Shard> shards;
  std::vector<std::string> problems;
  for (const fs::path& dir : o.shards) {
    try {
      shards.push_back(read_shard(dir));
    } catch (const MergeRefused& e) {
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
    }
  }
  if (!problems.empty()) throw MergeRefused(problems);
  check_one_run(shards, problems);
  std::vector<json> cases = gather_cases(shards, problems);
  if (!problems.empty()) throw MergeRefused(problems);

  json j = shards.front().report;
  ConformResult r = merged_result(j, cases, o.expectations);
  r.report_json = fs::absolute(o.out / "report.json");
  r.report_html = fs::absolute(o.out / "report" / "index.html");
  std::set<std::string> skipped;
  json provenance = json::array();
  double seconds = 0;
  for (const Shard& s : shards) {
    for (const json& k : s.report.value("skipped", json::array())) skipped.insert(k.get<std::string>());
    provenance.push_back({{"dir", fs::absolute(s.dir).string()}, {"index", s.index}, {"host", s.report.value("host", "")},
                          {"seconds", s.report.value("seconds", 0.0)}, {"shard", s.report.value("shard", json())}});
    seconds = std::max(seconds, s.report.value("seconds", 0.0));  // the shards ran side by side
  }
  r.skipped.assign(skipped.begin(), skipped.end());
  std::error_code ec;
  fs::remove(r.report_json, ec);
  if (ec) throw outputs::FileError(r.report_json, "remove the previous report", ec.value());
  outputs::StagedFolder staged(r.report_html.parent_path());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Shard* from = nullptr;
    for (const Shard& s : shards)
      if (s.index == cases[i].value("shard", 0)) from = &s;
    copy_images(cases[i], from->dir / "report", staged);
    if (j["plan"].value("shards", 1) <= 1) cases[i].erase("shard");
  }
  j.erase("shard");
  j.erase("host");  // each case names its host; merged_from names each shard's
  j["generated"] = now_utc();
  j["command"] = o.command_line;
  j["seconds"] = seconds;
  j["merged_from"] = provenance;
  j["scenes"] = r.scenes;
  j["skipped"] = r.skipped;
  j["cases"] = cases;
  j["summary"] = summary_json(r.cases.size(), r.count(Status::Pass), r.count(Status::Warn), r.count(Status::Fail),
                              r.count(Status::XFail), r.count(Status::XPass), r.count(Status::Error), r.exit_code());
  j.erase("expectations");
  std::vector<CaseOutcome> outcomes;
  for (const CaseResult& c : r.cases) outcomes.push_back({c.scene, c.technique, c.status, c.outcome, c.environment});
  std::string update;
  if (!o.expectations.empty()) {
    std::vector<outputs::Environment> environments;
    for (const CaseResult& c : r.cases)
      if (std::find(environments.begin(), environments.end(), c.environment) == environments.end())
        environments.push_back(c.environment);
    r.stale = stale_lines(o.expectations, r.scenes, r.techniques, r.convention, environments);
    j["expectations"] = expectations_json(o.expectations, r.stale, j["cases"]);
    update = expectations_update_text(o.expectations, outcomes, r.stale, r.convention);
  }
  j["triage"] = triage_json(o.expectations, outcomes, r.stale, r.convention);
  publish_reports(j, staged, r.report_json, update);
  return r;
}

}  // namespace shadowref::conform
