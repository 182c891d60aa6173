// report_writer.cpp — report.json (every metric, versions, GL strings) and report/index.html.
//
// All or nothing (docs/output-contract.md): report/ is staged and renamed into place, every other
// file is written atomically, and report.json comes last — the one an earlier run left is removed
// first — so that a report.json means the run finished and report/, report.junit.xml and summary.md
// beside it are the same run's.
#include "report_writer.hpp"

#include <chrono>
#include <ctime>
#include <nlohmann/json.hpp>
#include <set>
#include <system_error>
#include <type_traits>
#include <variant>
#include <unistd.h>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/report/comparison_json.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/report/ci_summary.hpp"
#include "shadowref/report/html.hpp"
#include "shadowref/renderer/render_variants.hpp"
#include "shadowref/outputs/json_text.hpp"
#include "shadowref/record/case_record.hpp"
#include "shadowref/record/run_record.hpp"
#include "shadowref/conform/case_json.hpp"

namespace shadowref::conform {
namespace {

namespace fs = std::filesystem;
namespace key = record::key;
using nlohmann::json;

// Copies `from` to <report>/<rel> and returns rel; "" when `from` is missing (a case that ended in an
// ERROR before its image was written). A copy that fails is a FileError: the report is not written
// with holes the disk made.
std::string copy_in(const fs::path& from, const outputs::StagedFolder& report, const std::string& rel) {
  std::error_code ec;
  if (!fs::is_regular_file(from, ec)) return "";
  fs::create_directories((report.path() / rel).parent_path(), ec);
  if (ec) throw outputs::FileError((report.final_path() / rel).parent_path(), "create the folder", ec.value());
  outputs::copy_file_atomically(from, report.path() / rel);
  return rel;
}

// The machine a result came from (each case of a merged report says which).
std::string host_name() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

// The case's record (record/case_record.hpp): the keys every reader of report.json acts on. The
// judgement's keys are compare --json's too (case_json.hpp); the run adds the rest.
record::CaseRecord case_record(const CaseResult& c, const ConformResult& r, bool with_expectations) {
  record::CaseRecord k = judged_case(c.scene, c.expected, c.judgement ? &*c.judgement : nullptr);
  k.technique = c.technique;  // as run: an extra technique's own name
  k.status = c.status;
  k.seconds = c.seconds;
  k.host = host_name();
  if (r.plan.shards > 1) k.shard = static_cast<int>(r.plan.shard_of.at(c.scene) + 1);
  if (with_expectations) k.expectation = record::ExpectationRecord{c.outcome, c.expected_status, c.expected_line};
  k.error = c.error;
  return k;
}

// One case as report.json holds it, its images copied into the staged report folder.
json case_json(const CaseResult& c, const outputs::StagedFolder& staged, std::set<std::string>& scenes_copied,
               const ConformResult& r, bool with_expectations) {
  std::error_code ec;
  json k;
  record::write_case(case_record(c, r, with_expectations), k);
  k[key::kSceneFile] = fs::absolute(c.scene_file).string();
  k[key::kReferenceDir] = c.reference_dir.string();
  k[key::kCandidateDir] = c.candidate_dir.string();
  k[key::kFrameMs] = c.frame_ms;
  k[key::kNotes] = c.notes;
  if (!c.read_through_links.empty()) {
    json links = json::array();
    for (const auto& [file, target] : c.read_through_links) links.push_back({{"file", file}, {"resolves_to", target}});
    k[key::kReadThroughLinks] = links;
  }
  if (!c.judgement) {
    // An ERROR case before a verdict records the declaration's defaults, as every case has one.
    const outputs::CandidateDeclaration defaults;
    k[key::kCandidate] = json::parse(outputs::declaration_text(defaults));
    k[key::kCandidate]["defaulted"] = defaults.defaulted;
    return k;
  }
  write_judgement(*c.judgement, k);
  const compare::FolderComparison& comparison = c.judgement->comparison;
  // The images the page shows, per light: reference mask, candidate mask, error, candidate shaded.
  const std::string base = "img/" + c.scene + "/" + c.technique + "/";
  json lights = json::array();
  for (std::size_t i = 0; i < comparison.masks.size(); ++i) {
    const std::string& m = comparison.masks[i];
    json l;
    l["mask"] = m;
    l["reference"] = copy_in(c.reference_dir / m, staged, "img/" + c.scene + "/reference_" + m);
    const std::string d = outputs::decided_name(i, comparison.masks.size());
    l["decided"] = copy_in(c.reference_dir / d, staged, "img/" + c.scene + "/reference_" + d);
    l["candidate"] = copy_in(c.candidate_dir / m, staged, base + "candidate_" + m);
    const fs::path err = fs::path(c.error_images[i]).is_absolute() ? fs::path(c.error_images[i])
                                                                   : c.candidate_dir / c.error_images[i];
    l["error"] = copy_in(err, staged, base + fs::path(c.error_images[i]).filename().string());
    l["metrics"] = report::to_json(comparison.per_light[i].metrics);
    if (i < comparison.visibility.size() && comparison.visibility[i]) {
      // Soft shadows: the candidate's lit fraction and its error in visibility units.
      const std::size_t n = comparison.masks.size();
      const std::string vis = outputs::visibility_name(i, n);
      const std::string vis_err = outputs::per_light_name("visibility_error", "png", i, n);
      l[key::kCandidateVisibility] = copy_in(c.candidate_dir / vis, staged, base + "candidate_" + vis);
      l[key::kVisibilityError] = copy_in(err.parent_path() / vis_err, staged, base + vis_err);
      l["visibility"] = report::to_json(comparison.visibility[i]->metrics);
    }
    lights.push_back(l);
  }
  k[key::kLights] = lights;
  k[key::kShaded] = copy_in(c.candidate_dir / "shaded.png", staged, base + "shaded.png");
  if (!scenes_copied.count(c.scene)) {
    copy_in(c.reference_dir / "shaded.png", staged, "img/" + c.scene + "/reference_shaded.png");
    scenes_copied.insert(c.scene);
  }
  k[key::kReferenceShaded] = fs::is_regular_file(staged.path() / ("img/" + c.scene + "/reference_shaded.png"), ec)
                              ? json("img/" + c.scene + "/reference_shaded.png")
                              : json("");
  return k;
}

// What every shard of one run must share (the merge refuses shards that differ): the whole plan,
// the catalogue's identity and the run's declarations.
json plan_json(const ConformResult& r, const ConformOptions& o) {
  json scenes = json::array();
  for (const std::string& s : r.plan.scenes) scenes.push_back({{key::kScene, s}, {key::kShard, r.plan.shard_of.at(s) + 1}});
  json p = {{key::kScenes, scenes},           {key::kShards, r.plan.shards},     {"assignment", r.plan.assignment},
            {key::kTechniques, r.techniques}, {key::kConvention, r.convention},  {key::kCatalogue, r.plan.catalogue_id},
            {key::kControl, r.plan.control}};
  if (!o.shard_weights_file.empty()) p["weights_file"] = fs::absolute(o.shard_weights_file).string();
  return p;
}

json declarations_json(const ConformOptions& o) {
  json d = {{"mode", o.candidate_dir ? "candidate-dir" : "render"},
            {"backend", o.candidate_dir ? json() : json(renderer::to_string(o.backend))},
            {"shadow_map_size", o.shadow_map_size},
            {"resolution_scale", o.resolution_scale},
            {"resolution", {o.width, o.height}},
            {"samples_per_axis", o.reference.samples_per_axis}};
  // Our renders' correct variants, each under its row's key (renderer/render_variants.hpp).
  for (const renderer::RenderVariant& v : renderer::render_variants())
    std::visit(
        [&](auto member) {
          const auto& value = o.render_options.*member;
          if constexpr (std::is_enum_v<std::remove_cvref_t<decltype(value)>>)
            d[std::string(v.key)] = outputs::to_string(value);
          else
            d[std::string(v.key)] = value;
        },
        v.field);
  return d;
}

}  // namespace

json summary_json(std::size_t cases, std::size_t pass, std::size_t warn, std::size_t fail, std::size_t xfail, std::size_t xpass,
                  std::size_t error, int exit_code) {
  return {{"cases", cases}, {"pass", pass},   {"warn", warn},   {"fail", fail},
          {"xfail", xfail}, {"xpass", xpass}, {"error", error}, {"exit_code", exit_code}};
}

json expectations_json(const ci::Expectations& e, const std::vector<const ci::ExpectationLine*>& stale, const json& cases) {
  json files = json::array();
  for (const auto& f : e.files) files.push_back(fs::absolute(f).string());
  json counts = json::object();
  for (Outcome o : {Outcome::Expected, Outcome::NewFailure, Outcome::NewWarning, Outcome::Improvement, Outcome::Flake}) {
    std::size_t n = 0;
    for (const json& c : cases) n += c.contains(key::kExpectation) && c[key::kExpectation].value(key::kOutcome, "") == to_string(o);
    counts[to_string(o)] = n;
  }
  json st = json::array();
  for (const ci::ExpectationLine* l : stale) st.push_back({{key::kLine, l->where}, {key::kText, l->text}});
  return {{key::kFiles, files}, {key::kCounts, counts}, {key::kStale, st}, {key::kUpdate, "expectations-update.txt"}};
}

json triage_json(const ci::Expectations& e, const std::vector<ci::CaseOutcome>& cases, const std::vector<const ci::ExpectationLine*>& stale,
                 const std::string& convention) {
  json lines = json::array();
  for (const ci::CaseOutcome& c : cases)
    if (c.outcome == Outcome::NewFailure || c.outcome == Outcome::NewWarning)
      lines.push_back({{key::kScene, c.scene}, {key::kTechnique, c.technique}, {key::kLine, ci::known_line(c, convention)}});
  return {{key::kBase, ci::expectations_update_text(e, cases, stale, convention, false)}, {key::kCases, lines}};
}

void publish_reports(const json& j, outputs::StagedFolder& staged, const fs::path& report_json, const std::string& update) {
  report::write_html(j, staged.path() / "index.html");
  staged.commit();
  // For CI: a JUnit XML file and a Markdown summary beside report.json.
  report::write_junit(j, report_json.parent_path() / "report.junit.xml");
  report::write_markdown(j, report_json.parent_path() / "summary.md");
  if (!update.empty()) outputs::write_file_atomically(report_json.parent_path() / "expectations-update.txt", update);
  outputs::write_file_atomically(report_json, outputs::json_text(j, 2) + "\n");
}

std::string now_utc() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

void write_reports(const ConformResult& r, const ConformOptions& o, const fs::path& cache) {
  std::error_code ec;
  fs::remove(r.report_json, ec);
  if (ec) throw outputs::FileError(r.report_json, "remove the previous report", ec.value());
  outputs::StagedFolder staged(r.report_html.parent_path());
  const bool with_expectations = !o.expectations.empty();

  json j;
  j[key::kTool] = "shadowref";
  j[key::kVersion] = SHADOWREF_VERSION;
  j[key::kGenerated] = now_utc();
  j["command"] = o.command_line;
  j["host"] = host_name();
  j[key::kMode] = o.candidate_dir ? "candidate-dir" : "render";
  if (o.candidate_dir) {
    j[key::kCandidateDir] = fs::absolute(*o.candidate_dir).string();
    std::size_t linked = 0;
    for (const CaseResult& c : r.cases) linked += c.read_through_links.size();
    j["inputs_read_through_links"] = linked;  // each case's read_through_links names them
  }
  j[key::kBackend] = o.candidate_dir ? json() : json(renderer::to_string(o.backend));
  j[key::kGlApi] = o.candidate_dir ? json() : json(renderer::to_string(o.gl_api));
  j[key::kGl] = {{"vendor", r.gl_vendor}, {key::kRenderer, r.gl_renderer}, {key::kVersion, r.gl_version}};
  j[key::kConvention] = r.convention;
  j[key::kReference] = {{"producer", "shadowref reference (Embree 3)"},
                    {key::kSamplesPerAxis, o.reference.samples_per_axis},
                    {"cache", fs::absolute(cache).string()}};
  j[key::kSeconds] = r.seconds;
  j["reference_seconds"] = r.reference_seconds;
  j["phase_seconds"] = {{"render", r.phases.render}, {"write", r.phases.write}, {"judge", r.phases.judge},
                        {"error_images", r.phases.error_images}};
  json thresholds = json::array();
  for (const compare::Threshold* t : compare::all_thresholds()) thresholds.push_back(report::to_json(*t));
  j[key::kThresholds] = thresholds;
  j[key::kScenes] = r.scenes;
  j[key::kTechniques] = r.techniques;
  j[key::kPlan] = plan_json(r, o);
  j[key::kDeclarations] = declarations_json(o);
  j[key::kSkipped] = r.skipped;
  j["summary"] = summary_json(r.cases.size(), r.count(Status::Pass), r.count(Status::Warn), r.count(Status::Fail),
                              r.count(Status::XFail), r.count(Status::XPass), r.count(Status::Error), r.exit_code());

  json cases = json::array();
  std::set<std::string> scenes_copied;
  for (const CaseResult& c : r.cases) cases.push_back(case_json(c, staged, scenes_copied, r, with_expectations));
  j[key::kCases] = cases;
  if (o.shard) {
    // The control case (none only when a [skips] regex left it out).
    const json control = r.control ? json{{key::kScene, r.control->scene}, {key::kTechnique, r.control->technique},
                                          {key::kStatus, to_string(r.control->status)}}
                                   : json::object();
    j[key::kShard] = {{key::kIndex, o.shard->index + 1}, {key::kTotalShards, o.shard->total}, {key::kSource, o.shard->source},
                      {key::kScenes, r.scenes}, {key::kControl, control}};
  }
  std::vector<ci::CaseOutcome> outcomes;
  for (const CaseResult& c : r.cases) outcomes.push_back({c.scene, c.technique, c.status, c.outcome, c.environment});
  std::string update;
  if (with_expectations) {
    j[key::kExpectations] = expectations_json(o.expectations, r.stale, cases);
    update = ci::expectations_update_text(o.expectations, outcomes, r.stale, r.convention);
  }
  j[key::kTriage] = triage_json(o.expectations, outcomes, r.stale, r.convention);
  publish_reports(j, staged, r.report_json, update);
}

}  // namespace shadowref::conform
