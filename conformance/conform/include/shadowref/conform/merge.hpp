// shadowref/conform/merge.hpp — one report from the shards of a split run (docs/ci.md): report.json,
// report/index.html, report.junit.xml, summary.md (and expectations-update.txt) as the run would
// have written them unsplit, each case saying which shard and host judged it.
//
// The shards must be one run: every report.json present (a shard that did not finish has none), the
// same suite version, catalogue, convention, declarations and plan (every shard records the whole
// plan: every scene and its shard), each shard exactly once, each planned case exactly once and from
// the shard the plan gives it (or left out by a [skips] regex), and every shard's control case with
// the same status (machines that judge the same case differently are not one run). Anything else is
// refused, one line per problem, and nothing is written.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadowref/conform/conform.hpp"
#include "shadowref/ci/expectations.hpp"

namespace shadowref::conform {

struct MergeOptions {
  std::vector<std::filesystem::path> shards;  // each a shard's --out folder
  std::filesystem::path out;
  ci::Expectations expectations;              // applied to the merged cases; empty: none
  std::string command_line;                   // recorded in report.json
};

// Thrown when the shards are not one complete run: one line per problem, in `problems`.
class MergeRefused : public std::invalid_argument {
 public:
  explicit MergeRefused(std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// Merges and writes the report under options.out. The result holds the merged cases (scene,
// technique, status, outcome; shard and host are in report.json) in the unsplit run's order, for the
// table and the exit code. Throws MergeRefused, std::invalid_argument for a report.json that does not
// parse, outputs::FileError when --out cannot be written.
ConformResult merge_shards(const MergeOptions& options);

}  // namespace shadowref::conform
