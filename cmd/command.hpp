// command.hpp — what every `shadowref` subcommand shares: the exit codes scripts rely on, the
// exception that carries a one-line bad-input message, and the registration signature.
#pragma once

#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace CLI {
class App;
class Validator;
}

namespace shadowref {
struct RunConvention;
}
namespace shadowref::renderer {
struct RenderOptions;
}
namespace shadowref::ci {
struct Expectations;
}
namespace shadowref::conform {
struct ConformResult;
struct ConformOptions;
}

namespace shadowref::cli {

// docs/output-contract.md: 0 pass, 1 warnings, 2 failures, 3 size mismatch, 4 bad input or file
// error, 5 internal error (a failed GL context, an Embree error, a broken invariant: never the
// user's input). `diff` answers a question rather than judging: 0 nothing changed, 1 changes found.
enum ExitCode : int {
  kExitPass = 0,
  kExitWarnings = 1,
  kExitChanged = 1,
  kExitFailures = 2,
  kExitSizeMismatch = 3,
  kExitBadInput = 4,
  kExitInternal = 5,
};

// Thrown for anything wrong with the input (an argument, a file, a JSON path). main() prints
// "shadowref <subcommand>: <what>" as one line on stderr and exits with kExitBadInput.
class BadInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The exit code and the one line main() prints for an exception that escaped a subcommand:
// the user's input (BadInput, a scene or mesh file, a mask, an unwritable output, an invalid
// option) → 3 or 4; anything else → kExitInternal, with "internal error" in the line.
struct ErrorReport {
  int exit_code;
  std::string line;
};
ErrorReport report_error(const std::exception& e);

// `--convention NAME`: adds the option (default "gl", the list and each one's summary in its help).
void add_convention_option(CLI::App& cmd, std::string& name);
// The run convention called `name`; BadInput naming the option and the known names otherwise.
const RunConvention& parse_convention(const std::string& name);

// `--shadow-map-size`'s check (outputs/limits.hpp): 0 (automatic) or a size in the limits; the
// same line in every subcommand that takes it.
CLI::Validator shadow_map_size_check();

// `--expectations FILE` (repeatable) in conform, compare and merge (expectations_option.cpp); the
// files read (BadInput naming the file and line); the terminal's lines for each new failure, new
// warning, improvement, stale line and skipped case, and the counts.
void add_expectations_option(CLI::App& cmd, std::vector<std::string>& files);
ci::Expectations read_expectations_option(const std::vector<std::string>& files);
void print_expectation_lines(const conform::ConformResult& r, const ci::Expectations& e);

// `conform`'s --shard K/N and --shard-weights FILE (shard_option.cpp); applying them sets the
// options' shard from the flag, else from a CI system's environment, reads the weights (BadInput
// naming the flag or the variables) and touches the runner's shard status file.
struct ShardArgs {
  std::string shard;
  std::string weights;
};
void add_shard_options(CLI::App& cmd, ShardArgs& args);
void apply_shard_options(const ShardArgs& args, conform::ConformOptions& options);
// Copies `junit` to $XML_OUTPUT_FILE when the test runner (Bazel) set it.
void write_xml_output_file(const std::filesystem::path& junit);

// Adds one subcommand to `app`. Its callback stores the exit code in `exit_code`.
using RegisterCommand = void (*)(CLI::App& app, int& exit_code);

void register_math_command(CLI::App& app, int& exit_code);
// `math mesh-report` and `math silhouette`, added to the `math` subcommand (math_mesh_command.cpp).
void register_math_mesh_commands(CLI::App& math, int& exit_code);
void register_render_command(CLI::App& app, int& exit_code);
void register_reference_command(CLI::App& app, int& exit_code);
void register_compare_command(CLI::App& app, int& exit_code);
void register_conform_command(CLI::App& app, int& exit_code);
void register_export_command(CLI::App& app, int& exit_code);
void register_goldens_command(CLI::App& app, int& exit_code);
void register_merge_command(CLI::App& app, int& exit_code);
void register_diff_command(CLI::App& app, int& exit_code);

}  // namespace shadowref::cli
