// shard_plan.cpp — scene-to-shard assignment and the CI systems' sharding protocols (shard_plan.hpp).
#include "shadowref/ci/shard_plan.hpp"

#include "shadowref/record/case_record.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace shadowref::ci {
namespace {

std::optional<int> parse_int(std::string_view s) {
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

struct Protocol {
  const char* total;
  const char* index;
  int base;                  // what the first shard's index is
  const char* status_file;   // the file the runner wants touched, or nullptr
};

constexpr Protocol kProtocols[] = {
    {"TEST_TOTAL_SHARDS", "TEST_SHARD_INDEX", 0, "TEST_SHARD_STATUS_FILE"},
    {"GTEST_TOTAL_SHARDS", "GTEST_SHARD_INDEX", 0, "GTEST_SHARD_STATUS_FILE"},
    {"CI_NODE_TOTAL", "CI_NODE_INDEX", 1, nullptr},
};

}  // namespace

ShardSpec parse_shard_flag(const std::string& text) {
  const auto slash = text.find('/');
  const auto k = slash == std::string::npos ? std::nullopt : parse_int(std::string_view(text).substr(0, slash));
  const auto n = slash == std::string::npos ? std::nullopt : parse_int(std::string_view(text).substr(slash + 1));
  if (!k || !n || *n < 1 || *n > kMaxShards || *k < 1 || *k > *n)
    throw std::invalid_argument("--shard '" + text + "': expected K/N with 1 <= K <= N <= " + std::to_string(kMaxShards) +
                                " (1-based, e.g. 2/4)");
  return {*k - 1, *n, "--shard", {}};
}

std::optional<ShardSpec> shard_from_environment(const std::function<const char*(const char*)>& getenv) {
  for (const Protocol& p : kProtocols) {
    const char* total = getenv(p.total);
    if (!total) continue;
    const char* index = getenv(p.index);
    const auto n = parse_int(total);
    const auto k = index ? parse_int(index) : std::nullopt;
    if (!n || !k || *n < 1 || *n > kMaxShards || *k < p.base || *k >= *n + p.base)
      throw std::invalid_argument(std::string(p.total) + "=" + total + ", " + p.index + "=" + (index ? index : "(unset)") +
                                  ": expected a total in 1.." + std::to_string(kMaxShards) + " and an index in " +
                                  std::to_string(p.base) + ".." + (p.base ? "total" : "total-1"));
    ShardSpec s{*k - p.base, *n, p.total, {}};
    if (p.status_file)
      if (const char* f = getenv(p.status_file); f && *f) s.status_file = f;
    return s;
  }
  return std::nullopt;
}

std::uint64_t stable_hash(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::map<std::string, int> assign_shards(const std::vector<std::string>& scenes, int total,
                                         const std::map<std::string, double>& weights) {
  std::map<std::string, int> out;
  std::vector<std::pair<double, std::string>> weighed;
  for (const std::string& s : scenes) {
    const auto w = weights.find(s);
    if (w == weights.end()) out[s] = static_cast<int>(stable_hash(s) % static_cast<std::uint64_t>(total));
    else weighed.emplace_back(w->second, s);
  }
  // Longest processing time first: heaviest scene to the least loaded shard.
  std::sort(weighed.begin(), weighed.end(), [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
  std::vector<double> load(static_cast<std::size_t>(total), 0.0);
  for (const auto& [w, s] : weighed) {
    const auto least = std::min_element(load.begin(), load.end());
    *least += w;
    out[s] = static_cast<int>(least - load.begin());
  }
  return out;
}

std::map<std::string, double> read_shard_weights(const std::filesystem::path& report_json) {
  const std::string said = "--shard-weights " + report_json.string() + ": ";
  std::ifstream in(report_json);
  if (!in) throw std::invalid_argument(said + "cannot read the file");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) throw std::invalid_argument(said + "not a JSON object (a report.json)");
  if (!j.contains(record::key::kCases)) throw std::invalid_argument(said + "cases: missing (a report.json)");
  std::map<std::string, double> out;
  try {
    for (const record::CaseRecord& c : record::read_cases(j)) out[c.scene] += c.seconds;
  } catch (const record::RecordError& e) {
    throw std::invalid_argument(said + e.what());
  }
  return out;
}

}  // namespace shadowref::ci
