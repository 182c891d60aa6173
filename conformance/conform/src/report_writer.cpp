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

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/report/comparison_json.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/report/ci_summary.hpp"
#include "shadowref/report/html.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::conform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string now_utc() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

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

}  // namespace

void write_reports(const ConformResult& r, const ConformOptions& o, const fs::path& cache) {
  std::error_code ec;
  fs::remove(r.report_json, ec);
  if (ec) throw outputs::FileError(r.report_json, "remove the previous report", ec.value());
  outputs::StagedFolder staged(r.report_html.parent_path());
  const fs::path& report_dir = staged.path();

  json j;
  j["tool"] = "shadowref";
  j["version"] = SHADOWREF_VERSION;
  j["generated"] = now_utc();
  j["command"] = o.command_line;
  j["mode"] = o.candidate_dir ? "candidate-dir" : "render";
  if (o.candidate_dir) {
    j["candidate_dir"] = fs::absolute(*o.candidate_dir).string();
    std::size_t linked = 0;
    for (const CaseResult& c : r.cases) linked += c.read_through_links.size();
    j["inputs_read_through_links"] = linked;  // each case's read_through_links names them
  }
  j["backend"] = o.candidate_dir ? json() : json(renderer::to_string(o.backend));
  j["gl_api"] = o.candidate_dir ? json() : json(renderer::to_string(o.gl));
  j["gl"] = {{"vendor", r.gl_vendor}, {"renderer", r.gl_renderer}, {"version", r.gl_version}};
  j["convention"] = r.convention;
  j["reference"] = {{"producer", "shadowref reference (Embree 3)"},
                    {"samples_per_axis", o.reference.samples_per_axis},
                    {"cache", fs::absolute(cache).string()}};
  j["seconds"] = r.seconds;
  j["reference_seconds"] = r.reference_seconds;
  j["phase_seconds"] = {{"render", r.phases.render}, {"write", r.phases.write}, {"judge", r.phases.judge},
                        {"error_images", r.phases.error_images}};
  json thresholds = json::array();
  for (const compare::Threshold* t : compare::all_thresholds()) thresholds.push_back(report::to_json(*t));
  j["thresholds"] = thresholds;
  j["scenes"] = r.scenes;
  j["techniques"] = r.techniques;
  j["summary"] = {{"cases", r.cases.size()},         {"pass", r.count(Status::Pass)},   {"warn", r.count(Status::Warn)},
                  {"fail", r.count(Status::Fail)},   {"xfail", r.count(Status::XFail)}, {"xpass", r.count(Status::XPass)},
                  {"error", r.count(Status::Error)}, {"exit_code", r.exit_code()}};

  json cases = json::array();
  std::set<std::string> scenes_copied;
  for (const CaseResult& c : r.cases) {
    json k;
    k["scene"] = c.scene;
    k["scene_file"] = fs::absolute(c.scene_file).string();
    k["technique"] = c.technique;
    k["status"] = to_string(c.status);
    k["expected"] = !c.expected_pass ? "fail" : c.expected_warning ? "warn" : "pass";
    k["why"] = c.why;
    if (!c.signature.empty()) k["signature"] = c.signature;
    k["reference_dir"] = c.reference_dir.string();
    k["candidate_dir"] = c.candidate_dir.string();
    k["frame_ms"] = c.frame_ms;
    k["seconds"] = c.seconds;
    k["notes"] = c.notes;
    k["causes"] = c.causes;
    if (!c.unmet_expectation.empty()) k["unmet_expectation"] = c.unmet_expectation;
    if (!c.error.empty()) k["error"] = c.error;
    if (!c.read_through_links.empty()) {
      json links = json::array();
      for (const auto& [file, target] : c.read_through_links) links.push_back({{"file", file}, {"resolves_to", target}});
      k["read_through_links"] = links;
    }
    {
      const outputs::CandidateDeclaration& d = c.declaration;
      k["candidate"] = json::parse(outputs::declaration_text(d));
      k["candidate"]["defaulted"] = d.defaulted;
    }
    if (c.comparison) {
      k["comparison"] = report::to_json(*c.comparison);
      // The images the page shows, per light: reference mask, candidate mask, error, candidate shaded.
      const std::string base = "img/" + c.scene + "/" + c.technique + "/";
      json lights = json::array();
      for (std::size_t i = 0; i < c.comparison->masks.size(); ++i) {
        const std::string& m = c.comparison->masks[i];
        json l;
        l["mask"] = m;
        l["reference"] = copy_in(c.reference_dir / m, staged, "img/" + c.scene + "/reference_" + m);
        const std::string d = outputs::decided_name(i, c.comparison->masks.size());
        l["decided"] = copy_in(c.reference_dir / d, staged, "img/" + c.scene + "/reference_" + d);
        l["candidate"] = copy_in(c.candidate_dir / m, staged, base + "candidate_" + m);
        const fs::path err = fs::path(c.error_images[i]).is_absolute() ? fs::path(c.error_images[i])
                                                                       : c.candidate_dir / c.error_images[i];
        l["error"] = copy_in(err, staged, base + fs::path(c.error_images[i]).filename().string());
        l["metrics"] = report::to_json(c.comparison->per_light[i].metrics);
        if (i < c.comparison->visibility.size() && c.comparison->visibility[i]) {
          // Soft shadows: the candidate's lit fraction and its error in visibility units.
          const std::size_t n = c.comparison->masks.size();
          const std::string vis = outputs::visibility_name(i, n);
          const std::string vis_err = outputs::per_light_name("visibility_error", "png", i, n);
          l["candidate_visibility"] = copy_in(c.candidate_dir / vis, staged, base + "candidate_" + vis);
          l["visibility_error"] = copy_in(err.parent_path() / vis_err, staged, base + vis_err);
          l["visibility"] = report::to_json(c.comparison->visibility[i]->metrics);
        }
        lights.push_back(l);
      }
      k["lights"] = lights;
      k["shaded"] = copy_in(c.candidate_dir / "shaded.png", staged, base + "shaded.png");
      if (!scenes_copied.count(c.scene)) {
        copy_in(c.reference_dir / "shaded.png", staged, "img/" + c.scene + "/reference_shaded.png");
        scenes_copied.insert(c.scene);
      }
      k["reference_shaded"] = fs::is_regular_file(report_dir / ("img/" + c.scene + "/reference_shaded.png"), ec)
                                  ? json("img/" + c.scene + "/reference_shaded.png")
                                  : json("");
    }
    cases.push_back(k);
  }
  j["cases"] = cases;

  report::write_html(j, report_dir / r.report_html.filename());
  staged.commit();
  // For CI: a JUnit XML file and a Markdown summary beside report.json.
  report::write_junit(j, r.report_json.parent_path() / "report.junit.xml");
  report::write_markdown(j, r.report_json.parent_path() / "summary.md");
  outputs::write_file_atomically(r.report_json, outputs::json_text(j, 2) + "\n");
}

}  // namespace shadowref::conform
