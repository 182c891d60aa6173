// math_args_fuzzer.cpp — libFuzzer target: the argument parsing of `shadowref math` (CLI11 with
// the real registration, register_math_command, and the subcommands' callbacks: number lists,
// ranges, layouts, the mathlib calls behind them). The input is the command line after
// "shadowref", one argument per line. Refusals must be CLI::ParseError (CLI11's) or BadInput,
// exactly what main.cpp turns into one line and exit 4; any other exception is a finding.
// What the commands print goes to a null stream.
#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"

namespace {

struct NullBuffer : std::streambuf {
  int overflow(int c) override { return c; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static NullBuffer null;
  static std::streambuf* const quiet_out = std::cout.rdbuf(&null);
  static std::streambuf* const quiet_err = std::cerr.rdbuf(&null);
  (void)quiet_out;
  (void)quiet_err;
  std::vector<std::string> args;
  std::string cur;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\n') {
      args.push_back(cur);
      cur.clear();
    } else {
      cur.push_back(c);
    }
  }
  if (!cur.empty()) args.push_back(cur);
  if (args.size() > 64) return 0;
  CLI::App app{"shadowref"};
  app.require_subcommand(1);
  int exit_code = 0;
  shadowref::cli::register_math_command(app, exit_code);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError&) {
  } catch (const shadowref::cli::BadInput&) {
  }
  return 0;
}
