// diff_command.cpp — `shadowref diff RUN_A RUN_B [--out DIR] [--json]`: one finished run against
// another (conform/run_diff.hpp), e.g. yesterday's run and today's, or one engine's WebGL2 and
// WebGPU renders judged each as a run. Prints one line per changed case and the counts, or one JSON
// object with --json; with --out, writes DIR/diff.html and its images (conform/diff_folder.hpp).
// Exit: 0 nothing changed, 1 changes found (as diff(1): a difference is the answer, not a failure of
// either run), 4 bad input (a missing folder or report.json, a field that is not what conform
// writes: one line naming the file and the JSON path).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "shadowref/conform/diff_folder.hpp"
#include "shadowref/conform/run_diff.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::cli {
namespace {

struct DiffArgs {
  std::string run_a, run_b;
  std::string out;
  bool json = false;
};

int run_diff(const DiffArgs& a) {
  const conform::RunDiff d = conform::diff_runs(a.run_a, a.run_b);
  const std::filesystem::path page = a.out.empty() ? std::filesystem::path() : conform::write_diff_folder(d, a.out);
  const int code = d.changed() == 0 ? kExitPass : kExitChanged;
  if (a.json) {
    nlohmann::json out = conform::to_json(d);
    if (!page.empty()) out["page"] = page.string();
    out["exit_code"] = code;
    std::cout << outputs::json_text(out, 2) << "\n";
    return code;
  }
  std::printf("shadowref diff: A %s (convention %s), B %s (convention %s)\n", a.run_a.c_str(), d.convention_a.c_str(),
              a.run_b.c_str(), d.convention_b.c_str());
  for (const conform::CaseDiff& c : d.cases)
    if (c.changed()) std::printf("%s\n", conform::case_line(c).c_str());
  std::printf("%zu cases compared, %zu changed (%zu only in A, %zu only in B)\n", d.cases.size(), d.changed(), d.only_in_a(),
              d.only_in_b());
  if (!page.empty()) std::printf("page: %s\n", page.string().c_str());
  return code;
}

}  // namespace

void register_diff_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DiffArgs>();
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "One finished run against another (two `conform` or `merge` --out folders, each with its report.json): the cases "
      "whose status, wrong or unexplained pixel count (all lights) or candidate masks changed, and the cases in one run "
      "only; for a case in both, how many mask pixels differ between the two runs' candidate masks (every light, byte "
      "for byte, decided or not) - where two renders differ, e.g. one engine's WebGL2 and WebGPU runs. Cases are "
      "matched by scene@technique.");
  cmd->add_option("RUN_A", args->run_a, "run A's output folder (its report.json and report/)")->required();
  cmd->add_option("RUN_B", args->run_b, "run B's output folder, read against A")->required();
  cmd->add_option("--out", args->out,
                  "write DIR/diff.html, a static page with one row per changed case (both runs' status, wrong and unexplained "
                  "pixels, candidate masks and error images side by side, and the picture of where the masks differ), and "
                  "its images in DIR/diff-images/; nothing else is written");
  cmd->add_flag("--json", args->json, "print one JSON object instead of text");
  cmd->footer(
      "Prints one line per changed case and \"N cases compared, M changed\".\n"
      "Mask-difference picture (B read against A): red B shadowed where A is lit, blue B lit where A is shadowed, magenta a\n"
      "surface in one and none in the other, yellow another byte in the same mask class; dimmed where they agree.\n"
      "Exit: 0 nothing changed, 1 changes found, 4 bad input (a missing folder or report.json, or a report field that is not\n"
      "what conform writes: one line naming the file and the JSON path).");
  cmd->callback([args, &exit_code] { exit_code = run_diff(*args); });
}

}  // namespace shadowref::cli
