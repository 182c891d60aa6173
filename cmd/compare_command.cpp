// compare_command.cpp — `shadowref compare`: one candidate folder against one reference folder.
//
// Any producer's folder works (docs/output-contract.md): the reference's (mask, decided) against the
// renderer's or an engine team's mask(s). The threshold is the technique's (thresholds.hpp):
// --technique, else the candidate's render.json "technique", else the strictest. With --scene, a
// shadow-map technique's wrong pixels are explained by the same cause model `conform` uses (the
// scene, the candidate's candidate.json); without it nothing explains them (the strictest reading).
// Prints the numbers per mask and the verdict, or one JSON object with --json; writes the error
// image(s) with --out. Exit: 0 pass, 1 quality warning, 2 fail, 3 size mismatch, 4 bad input.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "command.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/scene/scene.hpp"
#include "shadowref/compare/compare.hpp"
#include "shadowref/report/comparison_json.hpp"
#include "shadowref/outputs/json_text.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/reference/causes.hpp"
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
};

// The technique named in the candidate's render.json, or "".
std::string technique_from_render_json(const std::filesystem::path& dir) {
  std::ifstream in(dir / "render.json");
  if (!in) return "";
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_object() && j.contains("technique") && j["technique"].is_string()) return j["technique"].get<std::string>();
  return "";
}

void print_metrics(const std::string& name, const compare::MaskMetrics& m) {
  std::printf("  %-12s %dx%d, %zu decided pixels with a surface: wrong %zu (%.4g %%) = %zu false shadow + %zu false light + "
              "%zu coverage; unexplained %zu (%.4g %% of %zu edge px, core %zu); %zu region(s), largest %zu px\n",
              name.c_str(), m.width, m.height, m.decided_surface, m.wrong, m.wrong_percent(), m.false_shadow,
              m.false_light, m.coverage, m.unexplained, 100 * m.unexplained_ratio(), m.edge_pixels, m.unexplained_core,
              m.regions, m.largest_region);
}

int run_compare(const CompareArgs& a) {
  std::string technique = a.technique;
  std::string technique_source = "--technique";
  if (!technique.empty() &&
      !outputs::find_technique_name(technique)) {
    std::string known;
    for (const auto& t : outputs::kTechniques) known += (known.empty() ? "" : ", ") + std::string(t.name);
    throw BadInput("--technique '" + technique + "': unknown technique (expected one of " + known + ")");
  }
  if (technique.empty()) {
    technique = technique_from_render_json(a.candidate);
    technique_source = "render.json";
  }
  if (technique.empty()) technique_source = "none given: the strictest";
  const compare::Threshold& threshold = compare::threshold_for(technique);
  const RunConvention& convention = parse_convention(a.convention);
  // The cause model, when the scene is known: prepared at the size of the reference's masks (a
  // reference made at another resolution than the scene file's, e.g. conform --resolution).
  std::optional<scene::Scene> scene_file;
  std::optional<scene::PreparedScene> prepared;
  std::unique_ptr<reference::CauseModel> model;
  outputs::CandidateDeclaration declared;
  compare::Explainer explainer;
  compare::CompareOptions options;
  std::string causes = "none (no --scene: every wrong pixel is unexplained)";
  try {
    if (!a.scene.empty()) {
      scene_file = scene::load_scene(a.scene);
      const std::vector<std::string> masks = outputs::find_mask_names(a.reference);
      if (masks.size() != scene_file->lights.size())
        throw BadInput("--scene '" + a.scene + "': " + std::to_string(scene_file->lights.size()) + " light(s), but --reference has " +
                       std::to_string(masks.size()) + " mask(s)");
      const outputs::Image8 first = outputs::read_image8(std::filesystem::path(a.reference) / masks.front(), 1);
      scene_file->width = first.width;
      scene_file->height = first.height;
      options.no_cast_shadow_invariant = scene_file->invariant_no_cast_shadow;
      if (threshold.bands) {
        prepared = scene::prepare_scene(*scene_file, convention);
        declared = outputs::read_declaration(a.candidate, technique);
        model = std::make_unique<reference::CauseModel>(*prepared);
        explainer = [&](std::size_t light, int x, int y, bool candidate_lit) {
          return model->explain(light, x, y, declared, candidate_lit);
        };
        options.explain = &explainer;
        causes = "texel footprint and depth bias from " + a.scene + " and the candidate's declaration";
      } else {
        causes = "none (an exact technique has no texel or bias band)";
      }
    }
  } catch (const outputs::InputError& e) {
    throw BadInput(e.what());
  }
  compare::FolderComparison c;
  try {
    c = compare::compare_folders(a.reference, a.candidate, threshold, options);
  } catch (const compare::CompareError& e) {
    if (e.kind() == compare::CompareError::Kind::SizeMismatch) {
      std::cerr << "shadowref compare: size mismatch: " << e.what() << "\n";
      return kExitSizeMismatch;
    }
    throw BadInput(e.what());
  }
  std::vector<std::string> errors;
  if (!a.out.empty()) {
    try {
      errors = compare::write_error_images(c, a.out);
    } catch (const std::exception& e) {
      throw BadInput(e.what());
    }
  }
  const int code = c.judgement.verdict == compare::Verdict::Pass             ? kExitPass
                   : c.judgement.verdict == compare::Verdict::QualityWarning ? kExitWarnings
                                                                             : kExitFailures;
  if (a.json) {
    nlohmann::json j = report::to_json(c);
    j["reference"] = a.reference;
    j["candidate"] = a.candidate;
    j["technique"] = technique;
    j["causes"] = causes;
    j["error_images"] = errors;
    j["exit_code"] = code;
    std::cout << outputs::json_text(j, 2) << "\n";
    return code;
  }
  std::printf("shadowref compare: %s against %s\n", a.candidate.c_str(), a.reference.c_str());
  std::printf("  technique %s (%s), threshold %s: fail on any unexplained core or unexplained > %.4g %% of edge pixels\n",
              technique.empty() ? "-" : technique.c_str(), technique_source.c_str(), std::string(threshold.name).c_str(),
              100 * threshold.unexplained_fail);
  std::printf("  causes that explain wrong pixels: %s\n", causes.c_str());
  for (std::size_t i = 0; i < c.masks.size(); ++i) print_metrics(c.masks[i], c.per_light[i].metrics);
  if (c.masks.size() > 1) print_metrics("all lights", c.total);
  for (const std::string& e : errors) std::printf("  error image: %s\n", (std::filesystem::path(a.out) / e).string().c_str());
  std::string verdict = c.judgement.verdict == compare::Verdict::Pass             ? "PASS"
                        : c.judgement.verdict == compare::Verdict::QualityWarning ? "QUALITY WARNING"
                                                                                  : "FAIL";
  std::printf("verdict: %s\n", verdict.c_str());
  for (const std::string& r : c.judgement.reasons) std::printf("  %s\n", r.c_str());
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
                  "whose threshold judges (default: render.json's technique in the candidate folder, else the strictest)");
  cmd->add_option("--out", args->out, "write error.png (error_<i>.png per light) into this folder");
  cmd->add_option("--scene", args->scene,
                  "the scene both folders show: a shadow-map technique's wrong pixels are then explained by its texel "
                  "footprint and depth bias (the candidate's candidate.json), as conform does; without it, nothing is");
  add_convention_option(*cmd, args->convention);
  cmd->add_flag("--json", args->json, "print one JSON object instead of text");
  cmd->footer(
      "Error image: red = false shadow (reference lit), blue = false light (reference shadowed), magenta = "
      "coverage (surface vs no surface), green = undecided (not judged), grey = the dimmed reference.\n"
      "Exit: 0 pass, 1 quality warning, 2 fail, 3 size mismatch, 4 bad input.");
  cmd->callback([args, &exit_code] { exit_code = run_compare(*args); });
}

}  // namespace shadowref::cli
