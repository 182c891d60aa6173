// shadowref/ci/shard_plan.hpp — which shard of a split run judges which scene, and which shard
// this process is, read from the protocols CI systems already speak (docs/ci.md).
//
// The unit is the scene: its reference is computed once, in the one shard that has it. A scene goes
// to shard FNV-1a-64(name) mod N, so adding a scene to the catalogue moves that scene alone and no
// other. With recorded times (`--shard-weights`, a previous report.json's per-case `seconds`), the
// scenes it knows are dealt heaviest first to the least loaded shard (ties: the lower index; equal
// weights: by name), which balances time deterministically; a scene it does not know — one added
// since — still goes by its hash, so it moves nothing else.
//
// Protocols, in the order they are looked at (the first that is set wins; a flag beats them all):
//   --shard K/N                                    1-based (Playwright, GitLab)
//   TEST_TOTAL_SHARDS, TEST_SHARD_INDEX            0-based (Bazel); touch TEST_SHARD_STATUS_FILE
//   GTEST_TOTAL_SHARDS, GTEST_SHARD_INDEX          0-based (GoogleTest); touch GTEST_SHARD_STATUS_FILE
//   CI_NODE_TOTAL, CI_NODE_INDEX                   1-based (GitLab `parallel:`)
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadowref::ci {

struct ShardSpec {
  int index = 0;                        // 0-based
  int total = 1;
  std::string source;                   // "--shard", "TEST_TOTAL_SHARDS", "GTEST_TOTAL_SHARDS", "CI_NODE_TOTAL"
  std::filesystem::path status_file;    // the runner's proof-of-sharding file to touch, or empty
};

// "K/N" (1-based K in 1..N, N in 1..kMaxShards). Throws std::invalid_argument naming --shard.
ShardSpec parse_shard_flag(const std::string& text);

inline constexpr int kMaxShards = 4096;

// The first protocol of the environment that is set (`getenv` returns nullptr for unset), or none.
// Throws std::invalid_argument naming the variables when one is set and malformed (a total without
// an index, an index out of range, not a number).
std::optional<ShardSpec> shard_from_environment(const std::function<const char*(const char*)>& getenv);

// FNV-1a 64 of the bytes of `text`: the stable hash scenes are assigned by.
std::uint64_t stable_hash(std::string_view text);

// Scene name → shard (0-based) for `scenes` split `total` ways; `weights` (scene → seconds) may be
// empty. Deterministic: the same inputs give the same plan on every machine.
std::map<std::string, int> assign_shards(const std::vector<std::string>& scenes, int total,
                                         const std::map<std::string, double>& weights);

// The per-scene seconds a report.json recorded (the sum of its cases' `seconds` per scene).
// Throws std::invalid_argument naming the file and the JSON path for a file that is not one.
std::map<std::string, double> read_shard_weights(const std::filesystem::path& report_json);

}  // namespace shadowref::ci
