// conform.cpp — the conformance run (conform.hpp): references, renders, comparisons, statuses.
#include "shadowref/conform/conform.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

#include "linked_inputs.hpp"
#include "report_writer.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/scene/identifier.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/reference/causes.hpp"

namespace shadowref::conform {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int thread_count(int jobs) {
  if (jobs > 0) return jobs;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// The engine team's folder for a case: <dir>/<scene>/<technique>/ when it exists, else <dir>/<scene>/.
std::filesystem::path candidate_folder(const std::filesystem::path& dir, const std::string& scene,
                                       const std::string& technique) {
  std::error_code ec;
  const std::filesystem::path nested = dir / scene / technique;
  if (std::filesystem::is_directory(nested, ec)) return nested;
  return dir / scene;
}

// An expected failure that predicts the kind of its errors (scene::PredictedErrors): the errors of
// the other kind, judged on their own by the verdict's bounds (a 5x5 core, or a ratio to the same
// edge pixels or penumbra), must pass. Returns what they fail by, or "" when they pass; `seen`
// gets the predicted errors' counts for the signature.
std::string unpredicted_errors(const compare::FolderComparison& c, scene::PredictedErrors predicted, std::string& seen) {
  const bool light = predicted == scene::PredictedErrors::TooLight;
  const char* other_name = light ? "too dark (false shadow)" : "too light (false light)";
  std::string problem;
  const auto add = [&](const std::string& s) { problem += (problem.empty() ? "" : "; ") + s; };
  char buf[256];
  const compare::MaskMetrics& m = c.total;
  const std::size_t mask_other = light ? m.unexplained - m.unexplained_false_light : m.unexplained_false_light;
  // Cores of the other kind: all cores less the predicted kind's (a core of one kind is a core of both).
  const std::size_t mask_other_core = light ? m.unexplained_core - std::min(m.unexplained_core, m.unexplained_false_light_core)
                                            : m.unexplained_false_light_core;
  const double mask_ratio = m.edge_pixels ? static_cast<double>(mask_other) / static_cast<double>(m.edge_pixels) : 0.0;
  if (mask_other_core > 0 || (c.threshold && mask_ratio > c.threshold->unexplained_fail)) {
    std::snprintf(buf, sizeof buf, "mask: %zu px %s unexplained (%.2f %% of the edge pixels, %zu in cores)", mask_other,
                  other_name, 100.0 * mask_ratio, mask_other_core);
    add(buf);
  }
  std::size_t vis_predicted = 0;
  if (c.visibility_total) {
    const compare::VisibilityMetrics& v = *c.visibility_total;
    const std::size_t other = light ? v.unexplained - v.unexplained_too_light : v.unexplained_too_light;
    const std::size_t other_core = light ? v.unexplained_core - std::min(v.unexplained_core, v.unexplained_too_light_core)
                                         : v.unexplained_too_light_core;
    vis_predicted = v.unexplained - other;
    const double ratio = v.penumbra ? static_cast<double>(other) / static_cast<double>(v.penumbra) : 0.0;
    if (other_core > 0 || ratio > compare::kPenumbra.unexplained_fail) {
      std::snprintf(buf, sizeof buf, "lit fraction: %zu px %s unexplained (%.2f %% of the penumbra, %zu in cores)", other,
                    other_name, 100.0 * ratio, other_core);
      add(buf);
    }
  }
  std::snprintf(buf, sizeof buf, "%zu mask px and %zu lit-fraction px %s, unexplained", m.unexplained - mask_other,
                vis_predicted, light ? "too light" : "too dark");
  seen = buf;
  return problem;
}

}  // namespace

const char* to_string(Status s) {
  switch (s) {
    case Status::Pass: return "PASS";
    case Status::Warn: return "WARN";
    case Status::Fail: return "FAIL";
    case Status::XFail: return "XFAIL";
    case Status::XPass: return "XPASS";
    case Status::Error: return "ERROR";
  }
  return "?";
}

bool is_failure(Status s) { return s == Status::Fail || s == Status::XPass || s == Status::Error; }

Status status_of(compare::Verdict verdict, bool expected_pass) {
  if (expected_pass) {
    switch (verdict) {
      case compare::Verdict::Pass: return Status::Pass;
      case compare::Verdict::QualityWarning: return Status::Warn;
      case compare::Verdict::Fail: return Status::Fail;
    }
  }
  // An expected failure must fail outright: a pass or a mere quality warning means the known
  // limitation did not show, so the expectation (or the scene) is broken.
  return verdict == compare::Verdict::Fail ? Status::XFail : Status::XPass;
}

std::size_t ConformResult::count(Status s) const {
  return static_cast<std::size_t>(std::count_if(cases.begin(), cases.end(), [&](const CaseResult& c) { return c.status == s; }));
}

int ConformResult::exit_code() const {
  for (const CaseResult& c : cases)
    if (is_failure(c.status)) return 2;
  for (const CaseResult& c : cases)
    if (c.status == Status::Warn && !c.expected_warning) return 1;
  return 0;
}

ConformResult run_conform(const ConformOptions& o, const Progress& progress, const Log& log) {
  const auto say = [&](const std::string& s) {
    if (log) log(s);
  };
  const auto start = Clock::now();
  ConformResult result;

  // Techniques: ours must exist in the renderer; an engine team's may have any name (judged by
  // the strictest threshold unless it is one of ours).
  if (o.techniques.empty()) {
    if (o.candidate_dir) throw std::invalid_argument("--candidate-dir needs --technique (the name of the technique judged)");
    for (const renderer::Technique& t : renderer::techniques()) result.techniques.emplace_back(t.name);
  } else {
    for (const std::string& t : o.techniques) {
      // A technique's name becomes folder names under --out (renders/<scene>/<technique>,
      // errors/<scene>/<technique>): the scene files' safe-identifier rule holds for it too.
      if (const auto problem = scene::identifier_problem(t)) throw std::invalid_argument("--technique '" + t + "': " + *problem);
      const bool extra = std::any_of(o.extra_techniques.begin(), o.extra_techniques.end(),
                                     [&](const ExtraTechnique& e) { return e.name == t; });
      if (!o.candidate_dir && !extra && !renderer::find_technique(t))
        throw std::invalid_argument("unknown technique '" + t + "' (shadowref render --help lists them)");
      if (std::find(result.techniques.begin(), result.techniques.end(), t) == result.techniques.end())
        result.techniques.push_back(t);
    }
  }
  renderer::GlApi api{};
  renderer::Driver driver{};
  if (!o.candidate_dir && !o.references_only) {
    api = renderer::parse_gl_api(o.gl);
    driver = renderer::parse_driver(o.backend);
  }
  for (const ExtraTechnique& e : o.extra_techniques)
    if (!renderer::find_technique(e.renders))
      throw std::invalid_argument("variant '" + e.name + "' renders unknown technique '" + e.renders + "'");
  if (o.scenes.empty()) throw std::invalid_argument("no scenes selected");
  const RunConvention* convention = find_run_convention(o.convention);
  if (!convention) {
    std::string known;
    for (const RunConvention& c : kRunConventions) known += (known.empty() ? "" : ", ") + std::string(c.name);
    throw std::invalid_argument("--convention '" + o.convention + "': unknown (one of " + known + ")");
  }
  if (o.shadow_map_size != 0 && (o.shadow_map_size < 16 || o.shadow_map_size > 16384))
    throw std::invalid_argument("--shadow-map-size " + std::to_string(o.shadow_map_size) + ": must be 0 (automatic) or in [16, 16384]");
  result.convention = std::string(convention->name);

  if (!(o.resolution_scale > 0) || o.resolution_scale > 16)
    throw std::invalid_argument("--resolution-scale must be in (0, 16]");
  if ((o.width != 0) != (o.height != 0) || o.width < 0 || o.height < 0 || o.width > 16384 || o.height > 16384)
    throw std::invalid_argument("--resolution must be WxH with both in [1, 16384]");
  std::vector<scene::Scene> scenes;
  for (const auto& f : o.scenes) {
    scenes.push_back(scene::load_scene(f));
    scene::Scene& s = scenes.back();
    if (o.width) {
      s.width = o.width;
      s.height = o.height;
    }
    s.width = std::clamp(static_cast<int>(std::lround(s.width * o.resolution_scale)), 1, 16384);
    s.height = std::clamp(static_cast<int>(std::lround(s.height * o.resolution_scale)), 1, 16384);
    result.scenes.push_back(s.name);
  }
  // Everything that depends on the scene alone, once (scenes[] no longer moves).
  std::vector<scene::PreparedScene> prepared;
  scene::PrepareOptions prepare;
  prepare.shadow_map_size = o.shadow_map_size;
  for (const scene::Scene& s : scenes) prepared.push_back(scene::prepare_scene(s, *convention, prepare));

  // References, once per scene (the cache makes a second run free).
  const std::filesystem::path cache = o.cache.empty() ? o.out / "reference-cache" : o.cache;
  ReferenceSettings settings = o.reference;
  settings.threads = o.jobs;
  std::vector<std::filesystem::path> reference_dirs;
  const auto ref_start = Clock::now();
  for (const scene::PreparedScene& p : prepared) {
    const scene::Scene& s = *p.scene;
    const CachedReference r = ensure_reference(p, cache, settings);
    reference_dirs.push_back(r.dir);
    char buf[64];
    std::snprintf(buf, sizeof buf, "computed in %.1f s", r.seconds);
    say("reference " + s.name + ": " + (r.computed ? std::string(buf) : std::string("cached")) + " (" + r.dir.string() + ")");
  }
  result.reference_seconds = since(ref_start);
  if (o.references_only) {
    result.seconds = since(start);
    return result;
  }

  // The cause model of each scene (its BVH), built when a shadow-map case first needs it.
  std::vector<std::unique_ptr<reference::CauseModel>> causes(prepared.size());
  std::unique_ptr<renderer::Renderer> gl;
  std::unique_ptr<renderer::Renderer> model_gl;  // the techniques' models of their failures, for candidates
  if (!o.candidate_dir) {
    // llvmpipe's rasteriser threads; an explicit LP_NUM_THREADS in the environment wins.
    if (!std::getenv("LP_NUM_THREADS"))
      ::setenv("LP_NUM_THREADS", std::to_string(thread_count(o.jobs)).c_str(), 1);
    gl = std::make_unique<renderer::Renderer>(api, driver);
    result.gl_vendor = gl->info().vendor;
    result.gl_renderer = gl->info().renderer;
    result.gl_version = gl->info().version;
    say("OpenGL: " + result.gl_renderer + " (" + result.gl_version + ", " + o.gl + ")");
  }

  const std::size_t total = scenes.size() * result.techniques.size();
  for (std::size_t si = 0; si < scenes.size(); ++si) {
    const scene::Scene& s = scenes[si];
    for (const std::string& technique : result.techniques) {
      const auto case_start = Clock::now();
      CaseResult c;
      c.scene = s.name;
      c.scene_file = s.file;
      c.technique = technique;
      c.reference_dir = reference_dirs[si];
      const ExtraTechnique* extra = nullptr;
      std::string judged_as = technique;
      for (const ExtraTechnique& e : o.extra_techniques)
        if (e.name == technique) {
          extra = &e;
          judged_as = e.judged_as;
        }
      if (const auto e = s.expect.find(judged_as); e != s.expect.end()) {
        c.expected_pass = e->second.pass;
        c.expected_warning = e->second.warn;
        c.why = e->second.why;
        c.predicted_errors = e->second.errors;
      }
      try {
        if (gl) {
          c.candidate_dir = std::filesystem::absolute(o.out / "renders" / s.name / technique);
          renderer::RenderOptions render_options;
          if (extra) render_options.faults = extra->faults;
          auto t = Clock::now();
          const renderer::RenderResult r = gl->render(prepared[si], extra ? extra->renders : technique, render_options);
          result.phases.render += since(t);
          t = Clock::now();
          renderer::write_outputs(r, gl->info(), s, c.candidate_dir);
          result.phases.write += since(t);
          c.notes = r.notes;
          c.frame_ms = r.median_frame_ms();
        } else {
          c.candidate_dir = std::filesystem::absolute(candidate_folder(*o.candidate_dir, s.name, technique));
        }
        const auto judge_start = Clock::now();
        // What the candidate declares (candidate.json, ours written by the renderer), defaults otherwise.
        c.declaration = outputs::read_declaration(c.candidate_dir, judged_as);
        const compare::Threshold& threshold = compare::threshold_for(judged_as);
        compare::Explainer explainer;
        compare::CompareOptions copt;
        copt.no_cast_shadow_invariant = s.invariant_no_cast_shadow;
        if (threshold.bands) {
          if (!causes[si]) causes[si] = std::make_unique<reference::CauseModel>(prepared[si]);
          const reference::CauseModel& model = *causes[si];
          const outputs::CandidateDeclaration& declared = c.declaration;
          explainer = [&model, &declared](std::size_t light, int x, int y, bool candidate_lit) {
            return model.explain(light, x, y, declared, candidate_lit);
          };
          copt.explain = &explainer;
        }
        // Soft techniques: the lit fraction of every light with an area, judged in visibility units.
        compare::VisibilityExplainer visibility_explainer;
        const outputs::TechniqueName* named = outputs::find_technique_name(judged_as);
        if (named && named->family == outputs::TechniqueFamily::SoftShadow) {
          if (!causes[si]) causes[si] = std::make_unique<reference::CauseModel>(prepared[si]);
          const reference::CauseModel& model = *causes[si];
          const outputs::CandidateDeclaration& declared = c.declaration;
          visibility_explainer = [&model, &declared](std::size_t light, int x, int y) {
            const reference::CauseModel::Band b = model.visibility_band(light, x, y, declared);
            return std::make_pair(b.lo, b.hi);
          };
          copt.explain_visibility = &visibility_explainer;
          for (const scene::Light& l : s.lights) {
            const bool area = l.type == scene::LightType::Rect;
            copt.visibility_tolerance.push_back(area ? compare::visibility_sampling_tolerance(l.samples, declared.light_taps) : -1.0);
            copt.visibility_mean_error_bound.push_back(area ? compare::visibility_mean_error_bound(l.samples, declared.light_taps) : 0.0);
          }
        }
        c.comparison = compare::compare_folders(c.reference_dir, c.candidate_dir, threshold, copt);
        if (!gl) {
          std::vector<std::filesystem::path> read = {c.candidate_dir / outputs::kCandidateFile, c.candidate_dir / "shaded.png"};
          for (const std::string& m : c.comparison->masks) read.push_back(c.candidate_dir / m);
          for (const LinkedInput& l : inputs_outside(*o.candidate_dir, read)) c.read_through_links.emplace_back(l.file, l.resolves_to);
        }
        const std::filesystem::path error_dir =
            gl ? c.candidate_dir : std::filesystem::absolute(o.out / "errors" / s.name / technique);
        result.phases.judge += since(judge_start);
        const auto images_start = Clock::now();
        c.error_images = compare::write_error_images(*c.comparison, error_dir);
        result.phases.error_images += since(images_start);
        const auto signature_start = Clock::now();
        if (!gl) c.candidate_dir = std::filesystem::absolute(c.candidate_dir);
        c.status = status_of(c.comparison->judgement.verdict, c.expected_pass);
        // An expected failure that predicts its errors' kind: granted only when the other kind passes.
        if (c.status == Status::XFail && c.predicted_errors != scene::PredictedErrors::Any) {
          std::string seen;
          const std::string problem = unpredicted_errors(*c.comparison, c.predicted_errors, seen);
          if (!problem.empty()) {
            c.status = Status::Fail;
            c.signature = "expected failure seen, but errors of the kind it does not predict fail on their own: " + problem;
          } else {
            c.signature = "the errors are of the predicted kind: " + seen;
          }
        }
        if (!gl) {
          // Keep where the error images went for the report.
          for (auto& e : c.error_images) e = (error_dir / e).string();
        }
        // An expected failure is granted only when the candidate's errors are the ones the
        // technique's own model of its failure predicts: our implementation of the technique, which
        // shows the limitation exactly. The candidate is judged against the model's masks (on the
        // reference's decided pixels, with the same causes); what is left is wrong elsewhere.
        if (c.status == Status::XFail && !gl && renderer::find_technique(judged_as)) {
          if (!model_gl) model_gl = std::make_unique<renderer::Renderer>(renderer::GlApi::OSMesa, renderer::Driver::Llvmpipe);
          const std::filesystem::path model_dir = std::filesystem::absolute(o.out / "models" / s.name / judged_as);
          renderer::write_outputs(model_gl->render(prepared[si], judged_as), model_gl->info(), s, model_dir);
          for (std::size_t l = 0; l < s.lights.size(); ++l) {
            const std::string d = outputs::decided_name(l, s.lights.size());
            std::filesystem::copy_file(c.reference_dir / d, model_dir / d, std::filesystem::copy_options::overwrite_existing);
          }
          // The model is the technique's masks: a soft technique's lit fraction has no model of its
          // failure here (our render's fraction is no ground truth to measure an engine's against).
          compare::CompareOptions model_options = copt;
          model_options.visibility_tolerance.clear();
          model_options.visibility_mean_error_bound.clear();
          const compare::FolderComparison against_model =
              compare::compare_folders(model_dir, c.candidate_dir, threshold, model_options);
          if (against_model.judgement.verdict == compare::Verdict::Fail) {
            c.status = Status::Fail;
            c.signature = "expected failure seen, but also wrong elsewhere: " + std::to_string(against_model.total.unexplained) +
                          " px unexplained against the technique's own model of its failure (our " + judged_as + ")";
          } else {
            c.signature += std::string(c.signature.empty() ? "" : "; ") +
                           "the errors are the ones the technique's own model of its failure predicts (our " + judged_as + ")";
          }
        }
        result.phases.judge += since(signature_start);
      } catch (const std::exception& e) {
        c.status = Status::Error;
        c.error = e.what();
      }
      c.seconds = since(case_start);
      result.cases.push_back(std::move(c));
      if (progress) progress(result.cases.size(), total, result.cases.back());
    }
  }
  result.seconds = since(start);
  if (o.write_report) {
    result.report_json = std::filesystem::absolute(o.out / "report.json");
    result.report_html = std::filesystem::absolute(o.out / "report" / "index.html");
    write_reports(result, o, cache);
  }
  return result;
}

std::string table_text(const ConformResult& r) {
  std::size_t name_w = 5;
  for (const auto& s : r.scenes) name_w = std::max(name_w, s.size());
  std::map<std::pair<std::string, std::string>, const CaseResult*> at;
  for (const CaseResult& c : r.cases) at[{c.scene, c.technique}] = &c;
  std::vector<std::size_t> col_w;
  for (const auto& t : r.techniques) col_w.push_back(std::max<std::size_t>(t.size(), 5));
  std::string out;
  const auto pad = [](std::string s, std::size_t w) {
    if (s.size() < w) s += std::string(w - s.size(), ' ');
    return s;
  };
  out += pad("scene", name_w);
  for (std::size_t i = 0; i < r.techniques.size(); ++i) out += "  " + pad(r.techniques[i], col_w[i]);
  out += "\n";
  for (const auto& s : r.scenes) {
    out += pad(s, name_w);
    for (std::size_t i = 0; i < r.techniques.size(); ++i) {
      const auto it = at.find({s, r.techniques[i]});
      out += "  " + pad(it == at.end() ? "-" : to_string(it->second->status), col_w[i]);
    }
    out += "\n";
  }
  return out;
}

}  // namespace shadowref::conform
