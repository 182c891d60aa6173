// conform.cpp — the conformance run (conform.hpp): references, renders, comparisons, statuses.
#include "shadowref/conform/conform.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

#include "linked_inputs.hpp"
#include "report_writer.hpp"
#include "stall_watch.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/scene/identifier.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/interruption.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/outputs/spare_cores.hpp"

namespace shadowref::conform {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int thread_count(int jobs) { return jobs > 0 ? jobs : outputs::spare_cores(); }

// The engine team's folder for a case: <dir>/<scene>/<technique>/ when it exists, else <dir>/<scene>/.
std::filesystem::path candidate_folder(const std::filesystem::path& dir, const std::string& scene,
                                       const std::string& technique) {
  std::error_code ec;
  const std::filesystem::path nested = dir / scene / technique;
  if (std::filesystem::is_directory(nested, ec)) return nested;
  return dir / scene;
}

// Everything a run holds between its phases. The scenes do not move once prepared (the prepared
// scenes point at them).
struct Run {
  Run(const ConformOptions& options, const Log& l, ConformResult& r, StallWatch& w)
      : o(options), log(l), result(r), watch(w), judge(options.resolving_power) {}
  const ConformOptions& o;
  const Log& log;
  ConformResult& result;
  StallWatch& watch;
  std::vector<scene::Scene> scenes;
  std::vector<scene::PreparedScene> prepared;
  std::vector<std::filesystem::path> reference_dirs;
  std::filesystem::path cache;
  int threads = 1;  // --jobs, or the cores spare when the run starts (before our own threads load them)
  std::unique_ptr<renderer::Renderer> our_renderer;  // null: an engine team's candidates are judged
  // The index in `scenes` of the control case's scene when it is not this shard's own (judged for
  // the control alone), else none.
  std::optional<std::size_t> control_only;
  Judge judge;
  void say(const std::string& s) const {
    if (log) log(s);
  }
};

// Plan: the techniques asked for. Ours must exist in the renderer; an engine team's may have any
// safe name (judged by the strictest threshold unless it is one of ours).
std::vector<std::string> plan_techniques(const ConformOptions& o) {
  std::vector<std::string> out;
  if (o.techniques.empty()) {
    if (o.candidate_dir) throw std::invalid_argument("--candidate-dir needs --technique (the name of the technique judged)");
    for (const renderer::Technique& t : renderer::techniques()) out.emplace_back(t.name);
    return out;
  }
  for (const std::string& t : o.techniques) {
    // A technique's name becomes folder names under --out (renders/<scene>/<technique>,
    // errors/<scene>/<technique>): the scene files' safe-identifier rule holds for it too.
    if (const auto problem = scene::identifier_problem(t)) throw std::invalid_argument("--technique '" + t + "': " + *problem);
    const bool extra = std::any_of(o.extra_techniques.begin(), o.extra_techniques.end(),
                                   [&](const ExtraTechnique& e) { return e.name == t; });
    if (!o.candidate_dir && !extra && !renderer::find_technique(t))
      throw std::invalid_argument("unknown technique '" + t + "' (shadowref render --help lists them)");
    if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  }
  for (const ExtraTechnique& e : o.extra_techniques)
    if (!renderer::find_technique(e.renders))
      throw std::invalid_argument("extra technique '" + e.name + "' renders unknown technique '" + e.renders + "'");
  return out;
}

// Plan: the sizes, against the limits outputs/limits.hpp owns.
void check_sizes(const ConformOptions& o) {
  if (const std::string p = outputs::shadow_map_size_problem(o.shadow_map_size); !p.empty())
    throw std::invalid_argument("--shadow-map-size " + std::to_string(o.shadow_map_size) + ": " + p);
  if (!(o.resolution_scale > 0) || o.resolution_scale > 16) throw std::invalid_argument("--resolution-scale must be in (0, 16]");
  const int max = outputs::kMaxResolution;
  if ((o.width != 0) != (o.height != 0) || o.width < 0 || o.height < 0 || o.width > max || o.height > max)
    throw std::invalid_argument("--resolution must be WxH with both in [1, " + std::to_string(max) + "]");
  if (!o.convention) throw std::invalid_argument("no run convention");
}

// The catalogue's identity: FNV-1a 64 over every planned scene's name and file bytes, so that shards
// of one run can be checked to have judged the same scenes (the merge refuses others).
std::string catalogue_id(const std::vector<scene::Scene>& all) {
  std::string bytes;
  for (const scene::Scene& s : all) {
    std::ifstream in(s.file, std::ios::binary);
    bytes += s.name + '\0' + std::string(std::istreambuf_iterator<char>(in), {}) + '\0';
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "fnv1a64:%016llx", static_cast<unsigned long long>(ci::stable_hash(bytes)));
  return buf;
}

// Plan: every selected scene and its shard; this process keeps its shard's scenes and, when the run
// is split, the control case's scene: the plan's smallest (pixels x lights, then name), judged by
// every shard so that each proves it ran the judge, on the same case as the others.
void plan_scenes(Run& run) {
  const ConformOptions& o = run.o;
  if (o.scenes.empty()) throw std::invalid_argument("no scenes selected");
  std::vector<scene::Scene> all;
  for (const auto& f : o.scenes) {
    outputs::throw_if_interrupted();  // a scene of millions of triangles loads for seconds
    all.push_back(scene::load_scene(f));
  }
  RunPlan& plan = run.result.plan;
  for (const scene::Scene& s : all) plan.scenes.push_back(s.name);
  plan.shards = o.shard ? o.shard->total : 1;
  plan.assignment = o.shard_weights.empty() ? "hash" : "weights";
  plan.shard_of = ci::assign_shards(plan.scenes, plan.shards, o.shard_weights);
  plan.catalogue_id = catalogue_id(all);
  const scene::Scene* control = nullptr;
  if (o.shard) {
    const auto cost = [](const scene::Scene& s) { return static_cast<double>(s.width) * s.height * static_cast<double>(s.lights.size()); };
    for (const scene::Scene& s : all)
      if (!control || cost(s) < cost(*control) || (cost(s) == cost(*control) && s.name < control->name)) control = &s;
    plan.control = control->name;
  }
  run.scenes.reserve(all.size());
  for (scene::Scene& s : all) {
    const bool mine = !o.shard || plan.shard_of.at(s.name) == o.shard->index;
    if (!mine && &s != control) continue;
    if (!mine) run.control_only = run.scenes.size();
    run.scenes.push_back(std::move(s));
  }
}

// Prepare: every scene of this process at the run's resolution, and everything that depends on the
// scene alone.
void prepare(Run& run) {
  const ConformOptions& o = run.o;
  for (std::size_t i = 0; i < run.scenes.size(); ++i) {
    scene::Scene& s = run.scenes[i];
    if (o.width) {
      s.width = o.width;
      s.height = o.height;
    }
    s.width = std::clamp(static_cast<int>(std::lround(s.width * o.resolution_scale)), 1, outputs::kMaxResolution);
    s.height = std::clamp(static_cast<int>(std::lround(s.height * o.resolution_scale)), 1, outputs::kMaxResolution);
    if (run.control_only != i) run.result.scenes.push_back(s.name);
  }
  scene::PrepareOptions prepare;
  prepare.shadow_map_size = o.shadow_map_size;
  for (const scene::Scene& s : run.scenes) {
    outputs::throw_if_interrupted();
    run.prepared.push_back(scene::prepare_scene(s, *o.convention, prepare));
  }
}

// References: once per scene (the cache makes a second run free).
void compute_references(Run& run) {
  run.cache = run.o.cache.empty() ? run.o.out / "reference-cache" : run.o.cache;
  ReferenceSettings settings = run.o.reference;
  settings.threads = run.threads;
  const auto start = Clock::now();
  for (const scene::PreparedScene& p : run.prepared) {
    outputs::throw_if_interrupted();
    run.watch.step("computing the reference of " + p.scene->name);
    const CachedReference r = ensure_reference(p, run.cache, settings);
    if (!r.recomputed_because.empty())
      run.say("reference " + p.scene->name + ": the cached entry failed verification (" + r.recomputed_because + "): recomputed");
    run.reference_dirs.push_back(r.dir);
    char buf[64];
    std::snprintf(buf, sizeof buf, "computed in %.1f s", r.seconds);
    run.say("reference " + p.scene->name + ": " + (r.computed ? std::string(buf) : std::string("cached")) + " (" +
            r.dir.string() + ")");
  }
  run.result.reference_seconds = since(start);
}

// Draw: our renderer, unless an engine team's candidates are judged.
void open_renderer(Run& run) {
  if (run.o.candidate_dir) return;
  run.watch.step("opening the OpenGL context");
  run.our_renderer = std::make_unique<renderer::Renderer>(run.o.gl_api, run.o.backend);
  ConformResult& r = run.result;
  r.gl_vendor = run.our_renderer->info().vendor;
  r.gl_renderer = run.our_renderer->info().renderer;
  r.gl_version = run.our_renderer->info().version;
  run.say("OpenGL: " + r.gl_renderer + " (" + r.gl_version + ", " + renderer::to_string(run.o.gl_api) + ")");
}

// One case: draw (ours) or find (an engine's) the candidate, judge it, write its error images.
CaseResult run_case(Run& run, std::size_t si, const std::string& technique) {
  const ConformOptions& o = run.o;
  const scene::Scene& s = run.scenes[si];
  PhaseSeconds& phases = run.result.phases;
  CaseResult c;
  c.scene = s.name;
  c.scene_file = s.file;
  c.technique = technique;
  c.reference_dir = run.reference_dirs[si];
  const auto found = std::find_if(o.extra_techniques.begin(), o.extra_techniques.end(),
                                  [&](const ExtraTechnique& e) { return e.name == technique; });
  const ExtraTechnique* extra = found == o.extra_techniques.end() ? nullptr : &*found;
  const std::string judged_as = extra ? extra->judged_as : technique;
  if (const auto e = s.expect.find(judged_as); e != s.expect.end()) c.expected = e->second;
  const std::string name = s.name + " x " + technique;
  try {
    if (run.our_renderer) {
      c.candidate_dir = std::filesystem::absolute(o.out / "renders" / s.name / technique);
      renderer::RenderOptions render_options = o.render_options;
      if (extra) render_options.faults = extra->faults;
      auto t = Clock::now();
      run.watch.step("drawing " + name);
      const renderer::RenderResult r = run.our_renderer->render(run.prepared[si], extra ? extra->renders : technique, render_options);
      phases.render += since(t);
      t = Clock::now();
      run.watch.step("writing the render of " + name);
      renderer::write_outputs(r, run.our_renderer->info(), s, c.candidate_dir);
      phases.write += since(t);
      outputs::throw_if_interrupted();  // the render is published: stop before the judgement, not after it
      c.notes = r.notes;
      c.frame_ms = r.median_frame_ms();
    } else {
      c.candidate_dir = std::filesystem::absolute(candidate_folder(*o.candidate_dir, s.name, technique));
    }
    auto t = Clock::now();
    CaseToJudge what{c.reference_dir, c.candidate_dir, judged_as, run.our_renderer != nullptr,
                     std::filesystem::absolute(o.out / "models" / s.name / judged_as)};
    run.watch.step("judging " + name + " (its comparison and resolving power)");
    c.judgement = run.judge.judge(&run.prepared[si], what);
    c.environment = c.judgement->declaration.environment;
    phases.judge += since(t);
    c.status = c.judgement->status;
    if (!run.our_renderer) {
      std::vector<std::filesystem::path> read = {c.candidate_dir / outputs::kCandidateFile, c.candidate_dir / "shaded.png"};
      for (const std::string& m : c.comparison()->masks) read.push_back(c.candidate_dir / m);
      for (const LinkedInput& l : inputs_outside(*o.candidate_dir, read)) c.read_through_links.emplace_back(l.file, l.resolves_to);
    }
    outputs::throw_if_interrupted();
    t = Clock::now();
    run.watch.step("writing the error images of " + name);
    const std::filesystem::path error_dir = run.our_renderer ? c.candidate_dir : std::filesystem::absolute(o.out / "errors" / s.name / technique);
    c.error_images = compare::write_error_images(*c.comparison(), error_dir);
    // Keep where an engine's error images went, for the report.
    if (!run.our_renderer)
      for (auto& e : c.error_images) e = (error_dir / e).string();
    phases.error_images += since(t);
  } catch (const outputs::FileError&) {
    throw;  // --out cannot be written (a full disk): the run's failure, not this case's verdict
  } catch (const std::exception& e) {
    c.status = Status::Error;
    c.error = e.what();
  }
  return c;
}

}  // namespace

std::size_t ConformResult::count(Status s) const {
  return static_cast<std::size_t>(std::count_if(cases.begin(), cases.end(), [&](const CaseResult& c) { return c.status == s; }));
}

int ConformResult::exit_code() const {
  std::vector<Outcome> outcomes;
  for (const CaseResult& c : cases) outcomes.push_back(c.outcome);
  if (control) outcomes.push_back(control->outcome);
  return ci::exit_code(outcomes);
}

namespace {

// A judged case against the team's expectations files (expectations.hpp).
void classify(CaseResult& c, const ci::Expectations& e, const std::string& convention) {
  const ci::ExpectationLine* line = e.line_for(c.scene, c.technique, convention, c.environment);
  c.outcome = ci::outcome_of(c.status, c.expected.warn, line, e.flaky(ci::case_name(c.scene, c.technique, convention)));
  if (line) {
    c.expected_status = to_string(line->status);
    c.expected_line = line->where;
  }
}

// Judge: every case of this process's scenes, then (split runs) the control case.
void run_cases(Run& run, const Progress& progress) {
  const ConformOptions& o = run.o;
  ConformResult& result = run.result;
  std::size_t total = 0;
  for (std::size_t si = 0; si < run.scenes.size(); ++si)
    if (run.control_only != si) total += result.techniques.size();
  for (std::size_t si = 0; si < run.scenes.size(); ++si) {
    if (run.control_only == si) continue;
    for (const std::string& technique : result.techniques) {
      outputs::throw_if_interrupted();
      const std::string name = ci::case_name(run.scenes[si].name, technique, result.convention);
      if (o.expectations.skipped(name)) {
        result.skipped.push_back(name);
        continue;
      }
      const auto case_start = Clock::now();
      result.cases.push_back(run_case(run, si, technique));
      result.cases.back().seconds = since(case_start);
      run.watch.step("matching " + run.scenes[si].name + " x " + technique + " with the expectations");
      classify(result.cases.back(), o.expectations, result.convention);
      if (progress) progress(result.cases.size(), total, result.cases.back());
    }
  }
  if (result.plan.control.empty()) return;
  const std::string& technique = result.techniques.front();
  for (const CaseResult& c : result.cases)
    if (c.scene == result.plan.control && c.technique == technique) result.control = c;
  if (!result.control && run.control_only) {
    const auto case_start = Clock::now();
    result.control = run_case(run, *run.control_only, technique);
    result.control->seconds = since(case_start);
    run.watch.step("matching the control case " + result.plan.control + " x " + technique + " with the expectations");
    classify(*result.control, o.expectations, result.convention);
  }
}

}  // namespace

ConformResult run_conform(const ConformOptions& o, const Progress& progress, const Log& log, const Log& stalled) {
  const auto start = Clock::now();
  ConformResult result;
  result.techniques = plan_techniques(o);
  check_sizes(o);
  result.convention = std::string(o.convention->name);
  StallWatch watch(stalled, o.stall_report_after);
  watch.step("loading and preparing the scenes");
  Run run(o, log, result, watch);
  run.threads = thread_count(o.jobs);
  plan_scenes(run);
  prepare(run);
  compute_references(run);
  if (!o.references_only) {
    open_renderer(run);
    run_cases(run, progress);
    outputs::throw_if_interrupted();
    run.watch.step("matching the expectations (stale lines)");
    std::vector<outputs::Environment> environments;
    for (const CaseResult& c : result.cases)
      if (std::find(environments.begin(), environments.end(), c.environment) == environments.end())
        environments.push_back(c.environment);
    result.stale = ci::stale_lines(o.expectations, result.plan.scenes, result.techniques, result.convention, environments);
  }
  result.seconds = since(start);
  if (o.write_report && !o.references_only) {
    outputs::throw_if_interrupted();
    watch.step("writing the reports");
    result.report_json = std::filesystem::absolute(o.out / "report.json");
    result.report_html = std::filesystem::absolute(o.out / "report" / "index.html");
    write_reports(result, o, run.cache);
  }
  return result;
}

std::string table_cell(Status status, Outcome outcome, bool with_expectations) {
  std::string cell = to_string(status);
  if (!with_expectations) return cell;
  switch (outcome) {
    case Outcome::Expected: return cell + " known";
    case Outcome::NewFailure:
    case Outcome::NewWarning: return cell + " new";
    case Outcome::Improvement: return cell + " improved";
    case Outcome::Flake: return cell + " flaky";
    case Outcome::Green: return cell;
  }
  return cell;
}

std::string table_text(const ConformResult& r, bool with_expectations) {
  std::size_t name_w = 5;
  for (const auto& s : r.scenes) name_w = std::max(name_w, s.size());
  std::map<std::pair<std::string, std::string>, const CaseResult*> at;
  for (const CaseResult& c : r.cases) at[{c.scene, c.technique}] = &c;
  std::vector<std::size_t> col_w;
  for (const auto& t : r.techniques) col_w.push_back(std::max<std::size_t>(t.size(), with_expectations ? 14 : 5));
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
      const bool skipped = std::find(r.skipped.begin(), r.skipped.end(), ci::case_name(s, r.techniques[i], r.convention)) != r.skipped.end();
      out += "  " + pad(it != at.end() ? table_cell(it->second->status, it->second->outcome, with_expectations) : skipped ? "SKIP" : "-",
                        col_w[i]);
    }
    out += "\n";
  }
  return out;
}

}  // namespace shadowref::conform
