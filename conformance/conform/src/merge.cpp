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
#include "shadowref/record/run_record.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/staged_folder.hpp"

namespace shadowref::conform {
namespace {

namespace fs = std::filesystem;
namespace key = record::key;
using nlohmann::json;

struct Shard {
  fs::path dir;
  json report;        // as read, for the cases' keys the merged report carries whole
  record::RunRecord run;
  int index = 1, total = 1;  // 1-based; an unsplit run is shard 1/1
};

// A shard's report is read as every finished run's (run_report.hpp) and through its record once,
// so that a case or shard number of the wrong shape is refused with its JSON path before anything
// is merged (and every later reading holds).
Shard read_shard(const fs::path& dir) {
  Shard s;
  s.dir = dir;
  try {
    FinishedRun f = read_finished_run(dir);
    s.report = std::move(f.report);
    s.run = std::move(f.run);
  } catch (const ReportUnreadable& e) {
    throw MergeRefused({e.what()});
  }
  // A run without "shard" is shard 1/1; a "shard" without index or total says 0, which no plan has,
  // so that it is refused below as another plan's shard.
  if (s.run.shard) {
    s.index = s.run.shard->index;
    s.total = s.run.shard->total;
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
    const record::RunRecord &r = shards[i].run, &f = first.run;
    if (differs(shards[i], "suite version", r.version, f.version) || differs(shards[i], "catalogue", r.catalogue, f.catalogue) ||
        differs(shards[i], "convention", r.convention, f.convention) ||
        differs(shards[i], "declarations", r.declarations, f.declarations))
      continue;
    if (r.plan.whole != f.plan.whole)
      problems.push_back(shards[i].dir.string() + ": another plan than " + first.dir.string() +
                         "'s (other scenes, techniques, shard count or weights)");
  }
  const int total = first.run.plan.shards;
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
    for (const record::PlannedScene& p : first.run.plan.scenes)
      if (p.shard == k) scenes += (scenes.empty() ? "" : ", ") + p.scene;
    problems.push_back("shard " + std::to_string(k) + "/" + std::to_string(total) + " missing (its scenes: " +
                       (scenes.empty() ? "none" : scenes) + ")");
  }
}

// A case of the merged run: its keys as its shard wrote them (carried whole into the merged
// report), its record, and the shard it comes from.
struct MergedCase {
  json keys;
  record::CaseRecord rec;
  const Shard* from = nullptr;
};

// The control cases of every shard agree (the same machine judgement everywhere).
void check_controls(const std::vector<Shard>& shards, std::vector<std::string>& problems) {
  std::optional<Status> control_status;
  for (const Shard& s : shards) {
    if (!s.run.shard || !s.run.shard->control) continue;
    const record::ControlRecord& control = *s.run.shard->control;
    if (!control_status) control_status = control.status;
    else if (control.status != *control_status)
      problems.push_back(s.dir.string() + ": the control case " + control.scene + "@" + control.technique + " is " +
                         to_string(control.status) + " there and " + to_string(*control_status) + " in " +
                         shards.front().dir.string() + ": the shards' machines judge differently");
  }
}

// Each planned case once, from the shard the plan gives it; every shard's control case alike.
// Returns the cases in the unsplit run's order (plan scenes × techniques), each with its shard.
std::vector<MergedCase> gather_cases(const std::vector<Shard>& shards, std::vector<std::string>& problems) {
  const record::PlanRecord& plan = shards.front().run.plan;
  const std::string& convention = shards.front().run.convention;
  std::map<std::string, int> planned_shard;
  for (const record::PlannedScene& p : plan.scenes) planned_shard[p.scene] = p.shard;
  std::map<std::pair<std::string, std::string>, MergedCase> at;
  std::set<std::string> skipped;
  std::set<int> present_shards;
  for (const Shard& s : shards) {
    // A shard given twice is said once (check_one_run), not once more per case.
    if (!present_shards.insert(s.index).second) continue;
    skipped.insert(s.run.skipped.begin(), s.run.skipped.end());
    for (std::size_t i = 0; i < s.run.cases.size(); ++i) {
      MergedCase m{s.report[key::kCases][i], s.run.cases[i], &s};
      const std::string name = ci::case_name(m.rec.scene, m.rec.technique, convention);
      if (const auto it = at.find({m.rec.scene, m.rec.technique}); it != at.end()) {
        problems.push_back("case " + name + " seen twice: in " + it->second.from->dir.string() + " and " + s.dir.string());
        continue;
      }
      if (planned_shard.count(m.rec.scene) && planned_shard[m.rec.scene] != s.index && s.total > 1)
        problems.push_back("case " + name + " in " + s.dir.string() + " (shard " + std::to_string(s.index) +
                           "), but the plan gives it to shard " + std::to_string(planned_shard[m.rec.scene]));
      m.rec.shard = s.index;
      if (!m.rec.host) m.rec.host = s.run.host.value_or("");
      record::write_case(m.rec, m.keys);
      at[{m.rec.scene, m.rec.technique}] = std::move(m);
    }
  }
  std::vector<MergedCase> out;
  for (const record::PlannedScene& p : plan.scenes)
    for (const std::string& technique : plan.techniques) {
      const auto it = at.find({p.scene, technique});
      if (it != at.end()) {
        out.push_back(std::move(it->second));
        continue;
      }
      const std::string name = ci::case_name(p.scene, technique, convention);
      // A missing shard is said once, above, not once per case.
      if (!skipped.count(name) && present_shards.count(p.shard))
        problems.push_back("case " + name + " missing: planned for shard " + std::to_string(p.shard) + ", which does not have it");
    }
  check_controls(shards, problems);
  return out;
}

// Copies every image a case shows from its shard's report/ into the merged one (the record
// checked that each path stays in report/).
void copy_images(const MergedCase& c, const outputs::StagedFolder& staged) {
  const fs::path from_report = c.from->dir / "report";
  for (const std::string& rel : record::case_images(c.rec)) {
    std::error_code ec;
    if (fs::exists(staged.path() / rel, ec)) continue;  // a scene's reference images, shared by its cases
    fs::create_directories((staged.path() / rel).parent_path(), ec);
    if (ec) throw outputs::FileError((staged.final_path() / rel).parent_path(), "create the folder", ec.value());
    outputs::copy_file_atomically(from_report / rel, staged.path() / rel);
  }
}

// The merged cases as a ConformResult (table and exit code), each classified against `e`.
ConformResult merged_result(const record::RunRecord& first, std::vector<MergedCase>& cases, const ci::Expectations& e) {
  ConformResult r;
  r.convention = first.convention;
  for (const record::PlannedScene& p : first.plan.scenes) r.scenes.push_back(p.scene);
  r.techniques = first.plan.techniques;
  for (MergedCase& c : cases) {
    CaseResult k;
    k.scene = c.rec.scene;
    k.technique = c.rec.technique;
    k.status = c.rec.status;
    k.expected.warn = c.rec.expected == "warn";
    k.environment = c.rec.environment;  // as the shard wrote it
    const ci::ExpectationLine* line = e.line_for(k.scene, k.technique, r.convention, k.environment);
    k.outcome = ci::outcome_of(k.status, k.expected.warn, line, e.flaky(ci::case_name(k.scene, k.technique, r.convention)));
    c.keys.erase(key::kExpectation);
    c.rec.expectation.reset();
    if (!e.empty()) {
      c.rec.expectation = record::ExpectationRecord{k.outcome, line ? to_string(line->status) : "", line ? line->where : ""};
      record::write_case(c.rec, c.keys);
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
  std::vector<MergedCase> cases = gather_cases(shards, problems);
  if (!problems.empty()) throw MergeRefused(problems);

  json j = shards.front().report;
  ConformResult r = merged_result(shards.front().run, cases, o.expectations);
  r.report_json = fs::absolute(o.out / "report.json");
  r.report_html = fs::absolute(o.out / "report" / "index.html");
  std::set<std::string> skipped;
  json provenance = json::array();
  double seconds = 0;
  for (const Shard& s : shards) {
    skipped.insert(s.run.skipped.begin(), s.run.skipped.end());
    provenance.push_back({{"dir", fs::absolute(s.dir).string()}, {"index", s.index}, {"host", s.run.host.value_or("")},
                          {"seconds", s.run.seconds}, {"shard", s.run.shard ? s.run.shard->whole : json()}});
    seconds = std::max(seconds, s.run.seconds);  // the shards ran side by side
  }
  r.skipped.assign(skipped.begin(), skipped.end());
  std::error_code ec;
  fs::remove(r.report_json, ec);
  if (ec) throw outputs::FileError(r.report_json, "remove the previous report", ec.value());
  outputs::StagedFolder staged(r.report_html.parent_path());
  json merged_cases = json::array();
  for (MergedCase& c : cases) {
    copy_images(c, staged);
    if (shards.front().run.plan.shards <= 1) c.keys.erase(key::kShard);
    merged_cases.push_back(std::move(c.keys));
  }
  j.erase(key::kShard);
  j.erase(key::kHost);  // each case names its host; merged_from names each shard's
  j[key::kGenerated] = now_utc();
  j["command"] = o.command_line;
  j[key::kSeconds] = seconds;
  j["merged_from"] = provenance;
  j[key::kScenes] = r.scenes;
  j[key::kSkipped] = r.skipped;
  j[key::kCases] = merged_cases;
  j["summary"] = summary_json(r.cases.size(), r.count(Status::Pass), r.count(Status::Warn), r.count(Status::Fail),
                              r.count(Status::XFail), r.count(Status::XPass), r.count(Status::Error), r.exit_code());
  j.erase(key::kExpectations);
  std::vector<ci::CaseOutcome> outcomes;
  for (const CaseResult& c : r.cases) outcomes.push_back({c.scene, c.technique, c.status, c.outcome, c.environment});
  std::string update;
  if (!o.expectations.empty()) {
    std::vector<outputs::Environment> environments;
    for (const CaseResult& c : r.cases)
      if (std::find(environments.begin(), environments.end(), c.environment) == environments.end())
        environments.push_back(c.environment);
    r.stale = ci::stale_lines(o.expectations, r.scenes, r.techniques, r.convention, environments);
    j[key::kExpectations] = expectations_json(o.expectations, r.stale, j[key::kCases]);
    update = ci::expectations_update_text(o.expectations, outcomes, r.stale, r.convention);
  }
  j[key::kTriage] = triage_json(o.expectations, outcomes, r.stale, r.convention);
  publish_reports(j, staged, r.report_json, update);
  return r;
}

}  // namespace shadowref::conform
