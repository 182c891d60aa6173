// compare_command.cpp — `shadowref compare`: one candidate folder against one reference folder.
//
// Any producer's folder works (docs/output-contract.md): the reference's (mask, decided) against the
// renderer's or an engine team's mask(s). The verdict is the one judge's (conform/judge.hpp), as in
// `shadowref conform`: the technique is --technique, else the candidate's candidate.json
// "technique", else none (the strictest threshold); with --scene, wrong pixels are explained by the
// scene's cause model under the candidate's declaration, a soft technique's lit fraction is judged,
// and the scene file's expectation gives the case's status. Without --scene nothing explains a
// wrong pixel (the strictest reading) and a soft technique is refused. Prints the numbers per mask
// and the verdict, or with --json one case as conform's report.json holds it (conform/case_json.hpp:
// the same keys, with "technique_source", "error_images" and "exit_code" besides; without --scene,
// "scene" is "" and the status is the verdict's); writes the error image(s) with --out.
// Exit: 0 pass, 1 quality warning, 2 fail, 3 size mismatch, 4 bad input; with --scene, the case's
// status as conform's exit code reads it (status.hpp).
#include <CLI/CLI.hpp>

#include <chrono>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>

#include "command.hpp"
#include "shadowref/compare/compare.hpp"
#include "shadowref/conform/case_json.hpp"
#include "shadowref/ci/expectations.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/json_text.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::cli {
namespace {

struct CompareArgs {
  std::string reference;
  std::string candidate;
  std::string technique;
  std::string out;
  std::string scene;              // the scene both folders show: enables the cause model
  std::string convention = "gl";  // the run convention the scene is prepared in
  bool json = false;
  std::vector<std::string> expectations;
};

// The case against the expectations files (expectations.hpp): its outcome, the exit code that gives,
// and, with --out, the next file.
struct CaseAgainstFiles {
  conform::Outcome outcome = conform::Outcome::Green;
  const ci::ExpectationLine* line = nullptr;
  std::string name;
};

CaseAgainstFiles against_files(const ci::Expectations& e, const std::string& scene, const conform::CaseJudgement& j,
                               const CompareArgs& a) {
  CaseAgainstFiles f;
  f.name = ci::case_name(scene, j.technique, a.convention);
  f.line = e.line_for(scene, j.technique, a.convention, j.declaration.environment);
  f.outcome = ci::outcome_of(j.status, j.expectation.warn, f.line, e.flaky(f.name));
  if (!a.out.empty()) {
    const std::vector<ci::CaseOutcome> cases = {{scene, j.technique, j.status, f.outcome, j.declaration.environment}};
    outputs::write_file_atomically(std::filesystem::path(a.out) / "expectations-update.txt",
                                   ci::expectations_update_text(e, cases, {}, a.convention));
  }
  return f;
}

void print_metrics(const std::string& name, const compare::MaskMetrics& m) {
  std::printf("  %-12s %dx%d, %zu decided pixels with a surface: wrong %zu (%.4g %%) = %zu false shadow + %zu false light + "
              "%zu coverage; unexplained %zu (%.4g %% of %zu edge px, core %zu); %zu region(s), largest %zu px\n",
              name.c_str(), m.width, m.height, m.decided_surface, m.wrong, m.wrong_percent(), m.false_shadow,
              m.false_light, m.coverage, m.unexplained, 100 * m.unexplained_ratio(), m.edge_pixels, m.unexplained_core,
              m.regions, m.largest_region);
}

// The scene both folders show, prepared at the size of the reference's masks (a reference made at
// another resolution than the scene file's, e.g. conform --resolution).
struct KnownScene {
  scene::Scene file;
  std::optional<scene::PreparedScene> prepared;
};

std::unique_ptr<KnownScene> load_known_scene(const CompareArgs& a) {
  if (a.scene.empty()) return nullptr;
  auto known = std::make_unique<KnownScene>();
  known->file = scene::load_scene(a.scene);
  const std::vector<std::string> masks = outputs::find_mask_names(a.reference);
  if (masks.size() != known->file.lights.size())
    throw BadInput("--scene '" + a.scene + "': " + std::to_string(known->file.lights.size()) + " light(s), but --reference has " +
                   std::to_string(masks.size()) + " mask(s)");
  const outputs::Image8 first = outputs::read_image8(std::filesystem::path(a.reference) / masks.front(), 1);
  known->file.width = first.width;
  known->file.height = first.height;
  known->prepared = scene::prepare_scene(known->file, parse_convention(a.convention));
  return known;
}

// A scratch folder for the technique's model of its failure when --out is not given.
struct ScratchFolder {
  std::filesystem::path path;
  ScratchFolder() {
    path = std::filesystem::temp_directory_path() / ("shadowref-compare-" + std::to_string(::getpid()));
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

int run_compare(const CompareArgs& a) {
  const ci::Expectations expectations = read_expectations_option(a.expectations);
  if (!expectations.empty() && a.scene.empty())
    throw BadInput("--expectations needs --scene: a case is named scene@technique[@convention] in the files");
  if (!a.technique.empty() && !outputs::find_technique_name(a.technique)) {
    std::string known;
    for (const auto& t : outputs::kTechniques) known += (known.empty() ? "" : ", ") + std::string(t.name);
    throw BadInput("--technique '" + a.technique + "': unknown technique (expected one of " + known + ")");
  }
  conform::CaseJudgement j;
  ScratchFolder scratch;
  std::string scene_name;
  double seconds = 0;  // the judging's wall time, as a conform case's "seconds"
  try {
    const std::unique_ptr<KnownScene> known = load_known_scene(a);
    if (known) scene_name = known->file.name;
    const auto started = std::chrono::steady_clock::now();
    conform::Judge judge;
    const std::filesystem::path models = a.out.empty() ? scratch.path : std::filesystem::path(a.out) / "model";
    j = judge.judge(known ? &*known->prepared : nullptr, {a.reference, a.candidate, a.technique, false, models});
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (!a.technique.empty()) j.technique_source = "--technique";
  } catch (const outputs::InputError& e) {
    if (e.kind() == outputs::InputError::Kind::SizeMismatch) {
      std::cerr << "shadowref compare: size mismatch: " << e.what() << "\n";
      return kExitSizeMismatch;
    }
    throw BadInput(e.what());
  } catch (const scene::SceneError& e) {
    throw BadInput(e.what());
  }
  const compare::FolderComparison& c = j.comparison;
  std::vector<std::string> errors;
  if (!a.out.empty()) {
    try {
      errors = compare::write_error_images(c, a.out);
    } catch (const std::exception& e) {
      throw BadInput(e.what());
    }
  }
  // With the scene, the exit code is the case's status under its expectation, as conform's: an
  // expected failure seen as predicted (XFAIL) or an expected quality warning exits 0.
  std::optional<CaseAgainstFiles> files;
  if (!expectations.empty()) {
    if (!a.out.empty()) std::filesystem::create_directories(a.out);
    files = against_files(expectations, scene_name, j, a);
  }
  const int code = files ? ci::exit_code(std::vector<ci::Outcome>{files->outcome})
                   : !a.scene.empty() ? conform::exit_code({j.status}, {j.expectation.warn})
                   : c.decision.verdict == compare::Verdict::Pass             ? kExitPass
                   : c.decision.verdict == compare::Verdict::QualityWarning ? kExitWarnings
                                                                             : kExitFailures;
  if (a.json) {
    // conform's case shape (case_json.hpp), and what is compare's own.
    namespace key = record::key;
    record::CaseRecord rec = conform::judged_case(scene_name, j.expectation, &j);
    rec.seconds = seconds;
    if (files)
      rec.expectation = record::ExpectationRecord{files->outcome, files->line ? conform::to_string(files->line->status) : "",
                                                  files->line ? files->line->where : ""};
    nlohmann::json out;
    record::write_case(rec, out);
    conform::write_judgement(j, out);
    if (files) out[key::kExpectation][key::kCaseName] = files->name;
    out[key::kReferenceDir] = a.reference;
    out[key::kCandidateDir] = a.candidate;
    out[key::kTechniqueSource] = j.technique_source;
    out[key::kErrorImages] = errors;
    out[key::kExitCode] = code;
    std::cout << outputs::json_text(out, 2) << "\n";
    return code;
  }
  const compare::Threshold& threshold = *c.threshold;
  std::printf("shadowref compare: %s against %s\n", a.candidate.c_str(), a.reference.c_str());
  std::printf("  technique %s (from %s), threshold %s: fail on any unexplained core or unexplained > %.4g %% of edge pixels\n",
              j.technique.empty() ? "-" : j.technique.c_str(), j.technique_source.c_str(), std::string(threshold.name).c_str(),
              100 * threshold.unexplained_fail);
  std::printf("  causes that explain wrong pixels: %s\n", j.causes.c_str());
  for (std::size_t i = 0; i < c.masks.size(); ++i) print_metrics(c.masks[i], c.per_light[i].metrics);
  if (c.masks.size() > 1) print_metrics("all lights", c.total);
  if (c.visibility_total) {
    const compare::VisibilityMetrics& v = *c.visibility_total;
    std::printf("  lit fraction: %zu penumbra px, unexplained %zu (core %zu), mean |error| over the penumbra %.4g\n", v.penumbra,
                v.unexplained, v.unexplained_core, v.mean_penumbra_error());
  }
  for (const std::string& e : errors) std::printf("  error image: %s\n", (std::filesystem::path(a.out) / e).string().c_str());
  const std::string verdict = c.decision.verdict == compare::Verdict::Pass             ? "PASS"
                              : c.decision.verdict == compare::Verdict::QualityWarning ? "QUALITY WARNING"
                                                                                        : "FAIL";
  std::printf("verdict: %s\n", verdict.c_str());
  for (const std::string& r : c.decision.reasons) std::printf("  %s\n", r.c_str());
  // What the verdict could have seen: the reference's own masks with a blatant error each, judged
  // as this candidate was.
  if (j.resolving_power) std::printf("  resolving power: %s\n", j.resolving_power->summary().c_str());
  if (!a.scene.empty()) {
    std::printf("status under the scene's expectation: %s%s%s\n", conform::to_string(j.status),
                j.signature.empty() ? "" : ": ", j.signature.c_str());
    if (!j.unmet_expectation.empty()) std::printf("  %s\n", j.unmet_expectation.c_str());
  }
  if (files)
    std::printf("against the expectations files: %s is %s%s%s%s\n", files->name.c_str(), conform::to_string(files->outcome),
                files->line ? " (" : "", files->line ? (files->line->where + " expects " + conform::to_string(files->line->status)).c_str() : "",
                files->line ? ")" : "");
  return code;
}

}  // namespace

void register_compare_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare a candidate's mask(s) with the reference's on decided pixels: wrong pixels by kind, an error "
      "image, and the verdict against the technique's threshold.");
  cmd->add_option("--reference", args->reference, "the reference folder (mask.png or mask_<i>.png, decided.png or decided_<i>.png)")
      ->required();
  cmd->add_option("--candidate", args->candidate, "the candidate folder (the same mask names)")->required();
  cmd->add_option("--technique", args->technique,
                  "the technique judged: its threshold, causes and expectation (default: candidate.json's \"technique\" in "
                  "the candidate folder, else the strictest threshold)");
  cmd->add_option("--out", args->out, "write error.png (error_<i>.png per light) into this folder");
  cmd->add_option("--scene", args->scene,
                  "the scene both folders show: wrong pixels are then explained by the cause model under the candidate's "
                  "candidate.json, a soft technique's lit fraction is judged, and the scene's expectation gives a status, "
                  "exactly as conform does; without it nothing explains a wrong pixel, and soft techniques are refused");
  add_convention_option(*cmd, args->convention);
  cmd->add_flag("--json", args->json, "print the case as one JSON object, in the shape of a case of conform's report.json");
  add_expectations_option(*cmd, args->expectations);
  cmd->footer(
      "Error image: " + outputs::error_colours_line() + ".\n"
      "Exit: 0 pass, 1 quality warning, 2 fail, 3 size mismatch, 4 bad input; with --scene, the case's status under the "
      "scene's expectation as conform gives it (an XFAIL or an expected WARN exits 0, an XPASS 2); with --expectations (needs\n"
      "--scene), the case against those files: 0 as expected, 1 an improvement or a new warning, 2 a new failure.");
  cmd->callback([args, &exit_code] { exit_code = run_compare(*args); });
}

}  // namespace shadowref::cli
