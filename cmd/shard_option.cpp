// shard_option.cpp — `conform`'s share of a split run: --shard K/N, --shard-weights FILE, or the CI
// system's environment when no flag is given (conform/shard_plan.hpp names the protocols), the
// runner's status file touched, and the JUnit file copied where a runner asks for it (docs/ci.md).
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "command.hpp"
#include "shadowref/conform/conform.hpp"
#include "shadowref/ci/shard_plan.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"

namespace shadowref::cli {

void add_shard_options(CLI::App& cmd, ShardArgs& args) {
  cmd.add_option("--shard", args.shard,
                 "judge shard K of N (1-based, e.g. 2/4): the scenes a stable hash of their names gives it, and one control "
                 "case; without it TEST_TOTAL_SHARDS/TEST_SHARD_INDEX (Bazel), GTEST_TOTAL_SHARDS/GTEST_SHARD_INDEX (0-based) "
                 "or CI_NODE_TOTAL/CI_NODE_INDEX (GitLab, 1-based) are read; `shadowref merge` joins the shards (docs/ci.md)");
  cmd.add_option("--shard-weights", args.weights,
                 "a previous report.json: its per-case seconds balance the shards by time (scenes it lacks go by their hash)");
}

void apply_shard_options(const ShardArgs& args, conform::ConformOptions& o) {
  try {
    if (!args.shard.empty()) o.shard = ci::parse_shard_flag(args.shard);
    else o.shard = ci::shard_from_environment([](const char* name) { return std::getenv(name); });
    if (!args.weights.empty()) {
      if (!o.shard) throw std::invalid_argument("--shard-weights " + args.weights + ": needs a split run (--shard or a CI's shard variables)");
      o.shard_weights = ci::read_shard_weights(args.weights);
      o.shard_weights_file = args.weights;
    }
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  // The runner's proof that this binary shards (Bazel and GoogleTest check that it exists), touched
  // before any work: a shard that fails still understood the protocol.
  if (o.shard && !o.shard->status_file.empty()) {
    std::ofstream touch(o.shard->status_file, std::ios::app);
    if (!touch) throw outputs::FileError(o.shard->status_file, "touch the shard status file", errno);
  }
}

void write_xml_output_file(const std::filesystem::path& junit) {
  const char* target = std::getenv("XML_OUTPUT_FILE");
  if (!target || !*target) return;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(junit, ec)) return;
  outputs::copy_file_atomically(junit, target);
}

}  // namespace shadowref::cli
