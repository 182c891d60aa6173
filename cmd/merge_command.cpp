// merge_command.cpp — `shadowref merge DIR... --out DIR`: the shards of a split `conform` run joined
// into one report (conform/merge.hpp), its table and its exit code, as the run unsplit gives them.
// Shards that are not one complete run are refused, one line per problem, exit 4, nothing written.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "shadowref/conform/conform.hpp"
#include "shadowref/conform/merge.hpp"

namespace shadowref::cli {
namespace {

struct MergeArgs {
  std::vector<std::string> shards;
  std::string out = "conformance-merged";
  std::vector<std::string> expectations;
};

int run_merge(const MergeArgs& a) {
  conform::MergeOptions o;
  o.shards.assign(a.shards.begin(), a.shards.end());
  o.out = a.out;
  o.expectations = read_expectations_option(a.expectations);
  o.command_line = "shadowref merge";
  for (const std::string& s : a.shards) o.command_line += " " + s;
  o.command_line += " --out " + a.out;
  for (const std::string& e : a.expectations) o.command_line += " --expectations " + e;
  conform::ConformResult r;
  try {
    r = conform::merge_shards(o);
  } catch (const conform::MergeRefused& e) {
    for (const std::string& line : e.problems()) std::cerr << "shadowref merge: " << line << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  std::printf("%s\n", conform::table_text(r, !o.expectations.empty()).c_str());
  print_expectation_lines(r, o.expectations);
  std::printf("%zu cases from %zu shard(s): %zu PASS, %zu XFAIL, %zu FAIL, %zu XPASS, %zu WARN, %zu ERROR\n", r.cases.size(),
              a.shards.size(), r.count(conform::Status::Pass), r.count(conform::Status::XFail), r.count(conform::Status::Fail),
              r.count(conform::Status::XPass), r.count(conform::Status::Warn), r.count(conform::Status::Error));
  std::printf("report: %s\n        %s\n", r.report_html.string().c_str(), r.report_json.string().c_str());
  return r.exit_code();
}

}  // namespace

void register_merge_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Join the shards of a split `shadowref conform` run (each shard's --out folder) into one report.json, "
      "report/index.html, report.junit.xml and summary.md, as the run unsplit writes them; each case says its shard "
      "and host. Refuses shards that are not one complete run: a case seen twice, a missing case or shard, another "
      "suite version, catalogue, convention or declarations.");
  cmd->add_option("shards", args->shards, "the shards' output folders (each with its report.json)")->required();
  cmd->add_option("--out", args->out, "output folder: report.json, report/, report.junit.xml, summary.md")->capture_default_str();
  add_expectations_option(*cmd, args->expectations);
  cmd->footer(
      "Exit: as `conform`'s for the merged cases (0, 1 warnings or improvements, 2 failures or new failures), 4 when the\n"
      "shards are refused (one line each on stderr) or an argument or file is bad.");
  cmd->callback([args, &exit_code] { exit_code = run_merge(*args); });
}

}  // namespace shadowref::cli
