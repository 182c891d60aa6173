// main.cpp — the `shadowref` command: dispatches to the subcommands in kCommands.
//
// Every error ends here as one line on stderr: exit 4 (3 for a size mismatch) when the user's input
// or the environment (a full disk, no permission) caused it, 5 when it is an internal failure
// (report_error); SIGINT and SIGTERM stop the work at its next check, within about 2 s, and exit
// 128 + the signal (outputs/interruption.hpp); `--help` works on every level and exits 0.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "command.hpp"
#include "shadowref/outputs/interruption.hpp"

namespace {

using shadowref::cli::RegisterCommand;

// The subcommands, in the order `shadowref --help` lists them.
constexpr RegisterCommand kCommands[] = {
    shadowref::cli::register_math_command,
    shadowref::cli::register_render_command,
    shadowref::cli::register_reference_command,
    shadowref::cli::register_compare_command,
    shadowref::cli::register_conform_command,
    shadowref::cli::register_merge_command,
    shadowref::cli::register_diff_command,
    shadowref::cli::register_export_command,
    shadowref::cli::register_goldens_command,
};

// The deepest subcommand the user named.
const CLI::App* deepest(const CLI::App& app) {
  const CLI::App* cur = &app;
  while (!cur->get_subcommands().empty()) cur = cur->get_subcommands().front();
  return cur;
}

// "shadowref math perspective": the prefix of error messages.
std::string command_path(const CLI::App& app) {
  std::string path = "shadowref";
  const CLI::App* cur = &app;
  while (!cur->get_subcommands().empty()) {
    cur = cur->get_subcommands().front();
    path += " " + cur->get_name();
  }
  return path;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "shadowref — reference math, ground truth and conformance suite for real-time shadows.\n"
      "Exit codes: 0 pass, 1 warnings, 2 failures, 3 size mismatch, 4 bad input or file error, 5 internal error\n"
      "(diff: 0 nothing changed, 1 changes found)."};
  app.name("shadowref");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("shadowref ") + SHADOWREF_VERSION);
  int exit_code = shadowref::cli::kExitPass;
  for (RegisterCommand add : kCommands) add(app, exit_code);
  shadowref::outputs::install_interrupt_handlers();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A misspelt subcommand reaches us as "a subcommand is required" plus a leftover argument:
    // name the leftover, which is what the user needs to see.
    const std::vector<std::string> left = deepest(app)->remaining();
    if (!left.empty() && left.front().rfind("-", 0) != 0)
      std::cerr << command_path(app) << ": unknown subcommand '" << left.front() << "' (see --help)\n";
    else
      std::cerr << command_path(app) << ": " << e.what() << " (see --help)\n";
    return shadowref::cli::kExitBadInput;
  } catch (const std::exception& e) {
    const shadowref::cli::ErrorReport r = shadowref::cli::report_error(e);
    std::cerr << command_path(app) << ": " << r.line << "\n";
    return r.exit_code;
  } catch (const shadowref::outputs::Interrupted& stop) {
    std::cerr << command_path(app) << ": " << stop.message() << "\n";
    return 128 + stop.signal();
  }
  return exit_code;
}
