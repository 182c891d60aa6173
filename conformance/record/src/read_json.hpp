// read_json.hpp — the typed reads of report.json's values that the case and run records share: each
// names the JSON path of a value of the wrong type in its RecordError (internal to the record).
#pragma once

#include <cstdint>
#include <climits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowref/record/case_record.hpp"
#include "shadowref/record/comparison_record.hpp"

namespace shadowref::record::detail {

// The JSON path of `key` inside `where` ("" at the report's top level).
inline std::string path_at(const std::string& where, const char* key) { return where.empty() ? std::string(key) : where + "." + key; }

// j[key] (at `where`."key") as a string; `fallback` when absent or null.
inline std::string text_at(const nlohmann::json& j, const char* key, const std::string& where, const std::string& fallback = "") {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return fallback;
  if (!it->is_string()) throw RecordError(path_at(where, key) + ": must be a string, not " + it->dump());
  return it->get<std::string>();
}

// j[key], which is there, as a whole number from `least` to INT_MAX (a shard, an image height),
// never a float cast out of range.
inline int whole_at(const nlohmann::json& j, const char* key, const std::string& where, int least) {
  const nlohmann::json& v = j[key];
  const bool ok = v.is_number_integer() && (v.is_number_unsigned() ? v.get<std::uint64_t>() <= INT_MAX
                                                                   : v.get<std::int64_t>() >= least && v.get<std::int64_t>() <= INT_MAX);
  if (!ok || v.get<std::int64_t>() < least)
    throw RecordError(path_at(where, key) + ": must be a whole number from " + std::to_string(least) + " to " +
                      std::to_string(INT_MAX) + ", not " + v.dump());
  return static_cast<int>(v.get<std::int64_t>());
}

// j[key] as a number; nullopt when absent or null.
inline std::optional<double> number_at(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  if (!it->is_number()) throw RecordError(path_at(where, key) + ": must be a number, not " + it->dump());
  return it->get<double>();
}

// j[key] as a count (a whole number >= 0); nullopt when absent or null.
inline std::optional<long long> count_at(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  if (!it->is_number_integer() || (!it->is_number_unsigned() && it->get<std::int64_t>() < 0))
    throw RecordError(path_at(where, key) + ": must be a whole number >= 0, not " + it->dump());
  return it->get<long long>();
}

// j[key] as an array of strings (empty when absent).
inline std::vector<std::string> texts_at(const nlohmann::json& j, const char* key, const std::string& where) {
  std::vector<std::string> out;
  const auto it = j.find(key);
  if (it == j.end()) return out;
  if (!it->is_array()) throw RecordError(path_at(where, key) + ": must be an array of strings");
  for (const nlohmann::json& s : *it) {
    if (!s.is_string()) throw RecordError(path_at(where, key) + ": must be an array of strings, not with " + s.dump());
    out.push_back(s.get<std::string>());
  }
  return out;
}

// "PASS, WARN, FAIL, XFAIL, XPASS, ERROR", for a status outside the table.
inline std::string names_of_statuses() {
  std::string s;
  for (Status st : kStatuses) s += (s.empty() ? "" : ", ") + std::string(to_string(st));
  return s;
}

// j[key] (which must be there) as a status.
inline Status status_at(const nlohmann::json& j, const char* key, const std::string& where) {
  const std::string status = text_at(j, key, where);
  const std::optional<Status> st = status_from_string(status);
  if (!st) throw RecordError(path_at(where, key) + ": \"" + status + "\" is not a status (" + names_of_statuses() + ")");
  return *st;
}

// A mask's counts and a lit fraction at `where` (comparison_record.cpp): each value there of the
// wrong type is a RecordError at its path; an absent one is nullopt.
MaskMetricsRecord read_mask_metrics(const nlohmann::json& m, const std::string& where);
VisibilityRecord read_visibility(const nlohmann::json& v, const std::string& where);

}  // namespace shadowref::record::detail
