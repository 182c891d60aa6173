// run_command.hpp — runs a command line in a child process and captures what a script would see:
// the exit code, stdout and stderr. For tests of the `shadowref` command.
#pragma once

#include <string>
#include <vector>

namespace shadowref::test {

struct CommandResult {
  int exit_code = -1;  // the exit status, or 128 + signal number when the child was killed
  std::string out;
  std::string err;
};

// Runs `argv[0]` with arguments argv[1..] (no shell), waits for it, and captures both streams.
// `environment`: "NAME=value" entries set in the child on top of ours (LD_PRELOAD for a fault shim).
CommandResult run_command(const std::vector<std::string>& argv, const std::vector<std::string>& environment = {});

}  // namespace shadowref::test
