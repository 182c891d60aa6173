// convention_option.cpp — `--convention NAME`, the same for every subcommand that renders, traces
// or exports (command.hpp); the conventions themselves are mathlib's (convention.hpp).
#include <CLI/CLI.hpp>

#include "command.hpp"
#include "shadowref/convention.hpp"

namespace shadowref::cli {

void add_convention_option(CLI::App& cmd, std::string& name) {
  std::string help = "depth convention of the run:";
  for (const RunConvention& c : kRunConventions) help += "\n  " + std::string(c.name) + ": " + std::string(c.summary);
  cmd.add_option("--convention", name, help)->capture_default_str();
}

const RunConvention& parse_convention(const std::string& name) {
  if (const RunConvention* c = find_run_convention(name)) return *c;
  std::string known;
  for (const RunConvention& c : kRunConventions) known += (known.empty() ? "" : ", ") + std::string(c.name);
  throw BadInput("--convention '" + name + "': unknown convention (one of " + known + ")");
}

}  // namespace shadowref::cli
