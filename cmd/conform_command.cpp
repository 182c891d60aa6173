// conform_command.cpp — `shadowref conform`: the catalogue on one backend (or an engine team's
// renders) against the reference, a progress line per case, the scene × technique table, and
// report.json + report/index.html. Exit: 0 all PASS/XFAIL, 1 quality warnings, 2 any FAIL, XPASS
// or ERROR, 4 bad input.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "render_variant_options.hpp"
#include "numbers.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/conform.hpp"
#include "shadowref/ci/expectations.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/report/ci_summary.hpp"
#include "shadowref/renderer/gl_context.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::cli {
namespace {

struct ConformArgs {
  std::string scenes;
  std::string techniques;
  std::string technique;
  std::string convention = "gl";
  int shadow_map_size = 0;
  RenderVariantArgs variants;
  double resolution_scale = 1.0;
  std::string resolution;
  std::string backend = "llvmpipe";
  std::string gl = "osmesa";
  std::string out = "conformance-out";
  std::string cache;
  std::string catalogue;
  std::string candidate_dir;
  int jobs = 0;
  int spp = 16;
  bool references_only = false;
  bool no_resolving_power = false;
  bool quiet = false;
  std::vector<std::string> expectations;
  ShardArgs shard;
  std::vector<std::string> argv;
};

// What a shard of a split run judged, so that a log shows each shard ran its share.
void print_shard(const conform::ConformResult& r, const conform::ConformOptions& o) {
  if (!o.shard) return;
  std::string scenes;
  for (const std::string& s : r.scenes) scenes += (scenes.empty() ? "" : ", ") + s;
  std::printf("shard %d/%d (%s, by %s): %zu of %zu scenes: %s\n", o.shard->index + 1, o.shard->total, o.shard->source.c_str(),
              r.plan.assignment.c_str(), r.scenes.size(), r.plan.scenes.size(), scenes.empty() ? "none" : scenes.c_str());
  if (r.control)
    std::printf("control case %s: %s\n", ci::case_name(r.control->scene, r.control->technique, r.convention).c_str(),
                conform::to_string(r.control->status));
}

// Expected failures and failures with their why, so the table is never read without it.
void print_case_lines(const conform::ConformResult& r) {
  for (const conform::CaseResult& c : r.cases) {
    const compare::FolderComparison* comparison = c.comparison();
    if (c.status == conform::Status::Pass) {
      // An expectation the verdict did not meet is said, not hidden behind the PASS (status.hpp).
      if (c.judgement && !c.judgement->unmet_expectation.empty())
        std::printf("PASS   %s x %s: %s\n", c.scene.c_str(), c.technique.c_str(), c.judgement->unmet_expectation.c_str());
      continue;
    }
    std::printf("%-6s %s x %s", conform::to_string(c.status), c.scene.c_str(), c.technique.c_str());
    if (c.status == conform::Status::XFail || c.status == conform::Status::XPass) std::printf(": expected to fail: %s", c.expected.why.c_str());
    if (c.status == conform::Status::Warn && c.expected.warn) std::printf(": expected quality warning: %s", c.expected.why.c_str());
    if (comparison && c.status == conform::Status::XFail)
      std::printf(" (wrong %.3g %%, unexplained %zu px = %.3g %% of edges, core %zu px)", comparison->total.wrong_percent(),
                  comparison->total.unexplained, 100 * comparison->total.unexplained_ratio(), comparison->total.unexplained_core);
    if (comparison && comparison->visibility_total && c.status == conform::Status::XFail) {
      const compare::VisibilityMetrics& v = *comparison->visibility_total;
      std::printf(" (lit fraction: mean error %.3f over the penumbra, unexplained %zu px = %.3g %% of it, core %zu px)",
                  v.mean_penumbra_error(), v.unexplained, 100 * v.unexplained_ratio(), v.unexplained_core);
    }
    if (comparison && !comparison->decision.reasons.empty() && c.status != conform::Status::XFail) {
      std::string reasons;
      for (const std::string& reason : comparison->decision.reasons) reasons += (reasons.empty() ? "" : "; ") + reason;
      std::printf("%s%s", c.status == conform::Status::XPass ? "; but only " : ": ", reasons.c_str());
    }
    if (comparison && c.status == conform::Status::XPass && comparison->decision.reasons.empty())
      std::printf("; but it passed (wrong %.3g %%)", comparison->total.wrong_percent());
    if (c.judgement && !c.judgement->signature.empty()) std::printf("; %s", c.judgement->signature.c_str());
    if (!c.error.empty()) std::printf(": %s", c.error.c_str());
    std::printf("\n");
  }
}

// How many cases could not have seen a blatant error of some kind under their declaration, and how
// to sharpen them (tolerance/resolving_power.hpp).
void print_resolving_power(const conform::ConformResult& r, const conform::ConformOptions& o) {
  std::size_t judged = 0;
  std::size_t blind = 0;
  for (const conform::CaseResult& c : r.cases) {
    if (!c.judgement || !c.judgement->resolving_power) continue;
    ++judged;
    blind += !c.judgement->resolving_power->blind.empty();
  }
  if (!judged) {
    if (!r.cases.empty() && !o.resolving_power) std::printf("resolving power: not computed (--no-resolving-power)\n");
    return;
  }
  if (blind == 0) {
    std::printf("resolving power: none of %zu judged cases lets a probe that changes a decided pixel pass (report.json: resolving_power)\n", judged);
    return;
  }
  std::printf("resolving power: %zu of %zu judged cases are blind to a blatant error under their declaration "
              "(report.json: resolving_power); to sharpen them, %s\n",
              blind, judged, report::kHowToSharpen);
}

int run_conform_command(const ConformArgs& a) {
  conform::ConformOptions o;
  const std::filesystem::path catalogue = a.catalogue.empty() ? conform::default_catalogue() : std::filesystem::path(a.catalogue);
  try {
    o.scenes = conform::select_scenes(catalogue, conform::split_list(a.scenes));
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  o.techniques = conform::split_list(a.techniques);
  if (!a.technique.empty()) o.techniques.push_back(a.technique);
  o.convention = &parse_convention(a.convention);
  o.shadow_map_size = a.shadow_map_size;
  apply_render_variants(a.variants, a.shadow_map_size, o.render_options);
  o.resolution_scale = a.resolution_scale;
  if (!a.resolution.empty()) {
    const Size2 size = parse_size("--resolution", a.resolution, outputs::kMaxResolution);
    o.width = size.width;
    o.height = size.height;
  }
  try {
    o.backend = renderer::parse_driver(a.backend);
    o.gl_api = renderer::parse_gl_api(a.gl);
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  o.out = a.out;
  o.cache = a.cache;
  o.jobs = a.jobs;
  o.references_only = a.references_only;
  o.resolving_power = !a.no_resolving_power;
  int n = 1;
  while (n * n < a.spp) ++n;
  if (n * n != a.spp || n > 16) throw BadInput("--spp " + std::to_string(a.spp) + ": must be a square number in [1, 256]");
  o.reference.samples_per_axis = n;
  if (!a.candidate_dir.empty()) {
    if (!std::filesystem::is_directory(a.candidate_dir)) throw BadInput("--candidate-dir " + a.candidate_dir + ": not a folder");
    o.candidate_dir = a.candidate_dir;
  }
  for (const std::string& s : a.argv) o.command_line += (o.command_line.empty() ? "" : " ") + s;
  o.expectations = read_expectations_option(a.expectations);
  apply_shard_options(a.shard, o);
  // A test hook, not an option: the tests of SIGINT / SIGTERM in each stage of a run shorten the
  // stall watch's interval to see, in its lines, which stage the run has reached.
  if (const char* ms = std::getenv("SHADOWREF_STALL_REPORT_MS"); ms && std::atoi(ms) > 0)
    o.stall_report_after = std::chrono::milliseconds(std::atoi(ms));

  const bool tty = ::isatty(2);
  const auto progress = [&](std::size_t done, std::size_t total, const conform::CaseResult& c) {
    if (a.quiet) return;
    std::string detail;
    if (const compare::FolderComparison* comparison = c.comparison()) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%zu wrong (%.3g %%)", comparison->total.wrong, comparison->total.wrong_percent());
      detail = buf;
    } else {
      detail = c.error;
    }
    char head[64];
    std::snprintf(head, sizeof head, "[%3zu/%zu] ", done, total);
    std::cerr << (tty ? "\r\033[K" : "") << head << c.scene << " x " << c.technique << ": " << conform::to_string(c.status)
              << "  " << detail << " (" << static_cast<int>(c.seconds * 1000) << " ms)" << (tty && done < total ? "" : "\n")
              << std::flush;
  };
  const auto log = [&](const std::string& line) {
    if (!a.quiet) std::cerr << "shadowref conform: " << line << "\n";
  };
  // A step that has run for minutes is reported even with --quiet: it is a stall or a large scene.
  // On a terminal it takes the place of the unfinished progress line rather than running on after it.
  const auto stalled = [tty](const std::string& line) {
    std::cerr << (tty ? "\r\033[K" : "") << "shadowref conform: " << line << "\n" << std::flush;
  };
  conform::ConformResult r;
  try {
    r = conform::run_conform(o, progress, log, stalled);
  } catch (const scene::SceneError& e) {
    throw BadInput(e.what());
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  if (a.references_only) {
    std::printf("references of %zu scene(s) ready in %s (%.1f s)\n", r.scenes.size(),
                (a.cache.empty() ? (std::filesystem::path(a.out) / "reference-cache").string() : a.cache).c_str(),
                r.reference_seconds);
    return kExitPass;
  }
  std::printf("\n%s\n", conform::table_text(r, !o.expectations.empty()).c_str());
  print_case_lines(r);
  std::printf("\n%zu cases: %zu PASS, %zu XFAIL, %zu FAIL, %zu XPASS, %zu WARN, %zu ERROR in %.1f s (references %.1f s, "
              "drawing %.1f s, writing %.1f s, judging %.1f s, error images %.1f s)%s%s\n",
              r.cases.size(), r.count(conform::Status::Pass), r.count(conform::Status::XFail),
              r.count(conform::Status::Fail), r.count(conform::Status::XPass), r.count(conform::Status::Warn),
              r.count(conform::Status::Error), r.seconds, r.reference_seconds, r.phases.render, r.phases.write,
              r.phases.judge, r.phases.error_images,
              r.gl_renderer.empty() ? "" : ", ", r.gl_renderer.c_str());
  std::size_t linked = 0;
  for (const conform::CaseResult& c : r.cases) linked += c.read_through_links.size();
  if (linked)
    std::printf("note: %zu candidate file(s) were read through symbolic links that leave --candidate-dir "
                "(report.json: read_through_links)\n", linked);
  print_resolving_power(r, o);
  print_expectation_lines(r, o.expectations);
  print_shard(r, o);
  std::printf("report: %s\n        %s\n", r.report_html.string().c_str(), r.report_json.string().c_str());
  write_xml_output_file(r.report_json.parent_path() / "report.junit.xml");
  return r.exit_code();
}

}  // namespace

void register_conform_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ConformArgs>();
  CLI::App* cmd = app.add_subcommand(
      "conform",
      "Render the scene catalogue with every technique (or judge an engine team's renders), compare each with "
      "the reference, print the scene x technique table and write report.json and report/index.html.");
  cmd->add_option("--scenes", args->scenes, conform::kScenesHelp);
  cmd->add_option("--techniques", args->techniques, "comma-separated technique names (default: all)");
  cmd->add_option("--technique", args->technique, "one technique (the name an engine team's renders are judged as)");
  add_convention_option(*cmd, args->convention);
  cmd->add_option("--resolution", args->resolution, "render and judge every scene at WxH instead of its own resolution");
  cmd->add_option("--resolution-scale", args->resolution_scale,
                  "render and judge every scene at its resolution times this (e.g. 4: 256x256 becomes 1024x1024)")
      ->check(CLI::Range(0.0625, 16.0))
      ->capture_default_str();
  cmd->add_option("--shadow-map-size", args->shadow_map_size,
                  "texels per side of our shadow maps; 0: automatic (3 texels per camera pixel at the view centres)")
      ->check(shadow_map_size_check())
      ->capture_default_str();
  add_render_variant_options(*cmd, args->variants);
  cmd->add_option("--backend", args->backend, "Mesa driver: llvmpipe, softpipe, or native (a GPU's EGL)")->capture_default_str();
  cmd->add_option("--gl", args->gl, "context: osmesa or egl")->capture_default_str();
  cmd->add_option("--out", args->out, "output folder: renders/, report.json, report/index.html")->capture_default_str();
  cmd->add_option("--cache", args->cache, "reference cache folder (default: OUT/reference-cache)");
  cmd->add_option("--catalogue", args->catalogue, "scene folder (default: the installed catalogue; from the build tree, the source tree's)");
  cmd->add_option("--candidate-dir", args->candidate_dir,
                  "judge these renders instead of ours: DIR/<scene>/mask.png (or DIR/<scene>/<technique>/mask.png), "
                  "as `shadowref export` describes");
  cmd->add_option("--jobs", args->jobs, "threads for the reference (0: the cores the machine can spare, all less the one-minute load average, at least 1); llvmpipe always rasterises in the drawing thread")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  cmd->add_option("--spp", args->spp, "reference samples per pixel (a square number)")->capture_default_str();
  cmd->add_flag("--references-only", args->references_only, "compute the references into the cache and stop");
  cmd->add_flag("--no-resolving-power", args->no_resolving_power,
                "judge without the resolving power's probes: the same verdicts, metrics and statuses, in a fraction of "
                "the judging time; report.json then has no resolving_power");
  cmd->add_flag("--quiet", args->quiet, "no progress lines (a step still running after two minutes is reported all the same)");
  add_expectations_option(*cmd, args->expectations);
  add_shard_options(*cmd, args->shard);
  cmd->footer(
      "Status: PASS, WARN (quality warning), FAIL, XFAIL (an expected failure that failed: the catalogue's why),\n"
      "XPASS (an expected failure that passed: a broken expectation, counted as a failure), ERROR.\n"
      "Exit: 0 when every case is PASS, XFAIL or an expected WARN, 1 with other warnings, 2 with any FAIL, XPASS or ERROR, 4 bad input.\n"
      "With --expectations: a case as its line expects is no failure; 2 with a new failure, 1 with a new warning or an\n"
      "improvement (remove its line: OUT/expectations-update.txt is the next file), else 0.");
  cmd->callback([args, &exit_code] {
    // The effective command line, for report.json.
    ConformArgs& a = *args;
    a.argv = {"shadowref", "conform", "--backend", a.backend, "--gl", a.gl, "--out", a.out};
    if (!a.scenes.empty()) a.argv.insert(a.argv.end(), {"--scenes", a.scenes});
    if (!a.techniques.empty()) a.argv.insert(a.argv.end(), {"--techniques", a.techniques});
    if (!a.technique.empty()) a.argv.insert(a.argv.end(), {"--technique", a.technique});
    if (!a.candidate_dir.empty()) a.argv.insert(a.argv.end(), {"--candidate-dir", a.candidate_dir});
    for (const std::string& e : a.expectations) a.argv.insert(a.argv.end(), {"--expectations", e});
    if (!a.shard.shard.empty()) a.argv.insert(a.argv.end(), {"--shard", a.shard.shard});
    exit_code = run_conform_command(a);
  });
}

}  // namespace shadowref::cli
