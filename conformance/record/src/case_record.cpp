// case_record.cpp — a case of report.json read into its record and written from it (case_record.hpp).
#include "shadowref/record/case_record.hpp"

#include <algorithm>
#include <climits>
#include <filesystem>
#include <cstdint>

#include "read_json.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/record/run_record.hpp"  // key::kName, a threshold's name

namespace shadowref::record {
namespace {

using nlohmann::json;

using detail::text_at;
using detail::texts_at;

std::string where_of(std::size_t index) { return "cases[" + std::to_string(index) + "]"; }
std::string path_of(std::size_t index, const char* key) { return where_of(index) + "." + key; }

// c[key] as a string; `fallback` when absent or null. Another type is a RecordError at its path.
std::string text(const json& c, const char* key, std::size_t index, const std::string& fallback = "") {
  return text_at(c, key, where_of(index), fallback);
}

// c[key] as a number >= 0; `fallback` when absent or null. Another value is a RecordError at its path.
double number(const json& c, const char* key, std::size_t index, double fallback) {
  const auto it = c.find(key);
  if (it == c.end() || it->is_null()) return fallback;
  if (!it->is_number() || !(it->get<double>() >= 0))
    throw RecordError(path_of(index, key) + ": must be a number >= 0, not " + it->dump());
  return it->get<double>();
}

// Whether write_case writes a key whose row says `w` and whose value is set or not.
bool writes(Written w, bool set) { return w == Written::Always || (w == Written::WhenSet && set); }

// c[key], which is there, as a count from 0 (a shard, an image height).
int count(const json& c, const char* key, std::size_t index) { return detail::whole_at(c, key, where_of(index), 0); }

// What the page shows of "comparison" (absent or null before a verdict): the total counts, which
// must hold the counts two runs are compared by, its reasons, its threshold's name and the lights'
// lit fraction together.
void read_comparison(const json& c, std::size_t index, CaseRecord& r) {
  const auto cmp = c.find(key::kComparison);
  if (cmp == c.end() || cmp->is_null()) return;
  const std::string where = path_of(index, key::kComparison);
  const auto total = cmp->is_object() ? cmp->find(key::kTotal) : cmp->end();
  if (!cmp->is_object() || total == cmp->end() || !total->is_object())
    throw RecordError(where + "." + key::kTotal + ": missing or not an object");
  r.total = detail::read_mask_metrics(*total, where + "." + key::kTotal);
  if (!r.total->wrong) throw RecordError(where + "." + key::kTotal + "." + key::kWrong + ": missing");
  if (!r.total->unexplained) throw RecordError(where + "." + key::kTotal + "." + key::kUnexplained + ": missing");
  r.reasons = texts_at(*cmp, key::kReasons, where);
  if (const auto t = cmp->find(key::kThreshold); t != cmp->end() && !t->is_null()) {
    if (!t->is_object()) throw RecordError(where + "." + key::kThreshold + ": must be an object, not " + t->dump());
    r.threshold = text_at(*t, key::kName, where + "." + key::kThreshold);
  }
  if (const auto v = cmp->find(key::kVisibility); v != cmp->end()) r.visibility = detail::read_visibility(*v, where + "." + key::kVisibility);
}

// l[key]: an image path under report/, "" when absent, null or empty.
std::string image(const json& l, const char* key, const std::string& where) {
  const auto it = l.find(key);
  if (it == l.end() || it->is_null()) return "";
  if (!it->is_string()) throw RecordError(where + "." + key + ": must be a string, not " + it->dump());
  const std::string rel = it->get<std::string>();
  if (!rel.empty() && !inside_report_folder(rel)) throw RecordError(where + "." + key + ": '" + rel + "' leaves the report folder");
  return rel;
}

std::vector<LightRecord> read_lights(const json& c, std::size_t index) {
  std::vector<LightRecord> out;
  const auto lights = c.find(key::kLights);
  if (lights == c.end()) return out;
  if (!lights->is_array()) throw RecordError(path_of(index, key::kLights) + ": not an array");
  for (std::size_t i = 0; i < lights->size(); ++i) {
    const json& l = (*lights)[i];
    const std::string at = path_of(index, key::kLights) + "[" + std::to_string(i) + "]";
    if (!l.is_object()) throw RecordError(at + ": not an object");
    LightRecord r;
    const auto mask = l.find(key::kMask);
    if (mask == l.end() || !mask->is_string()) throw RecordError(at + "." + key::kMask + ": missing or not a string");
    r.mask = mask->get<std::string>();
    // The mask's name also names the page's copies: a plain file name.
    if (r.mask.empty() || std::filesystem::path(r.mask).filename() != r.mask || r.mask == "." || r.mask == "..")
      throw RecordError(at + "." + key::kMask + ": '" + r.mask + "' is not a mask file name");
    r.reference = image(l, key::kReference, at);
    r.decided = image(l, key::kDecided, at);
    r.candidate = image(l, key::kCandidate, at);
    r.error = image(l, key::kErrorImage, at);
    r.candidate_visibility = image(l, key::kCandidateVisibility, at);
    r.visibility_error = image(l, key::kVisibilityError, at);
    if (const auto m = l.find(key::kMetrics); m != l.end()) r.metrics = detail::read_mask_metrics(*m, at + "." + key::kMetrics);
    if (const auto v = l.find(key::kVisibility); v != l.end()) r.visibility = detail::read_visibility(*v, at + "." + key::kVisibility);
    out.push_back(std::move(r));
  }
  return out;
}

ExpectationRecord read_expectation(const json& e, std::size_t index) {
  const std::string where = path_of(index, key::kExpectation);
  if (!e.is_object()) throw RecordError(where + ": must be an object");
  ExpectationRecord r;
  const std::string outcome = text(e, key::kOutcome, index, "green");
  const std::optional<Outcome> o = outcome_from_string(outcome);
  if (!o) throw RecordError(where + "." + key::kOutcome + ": \"" + outcome + "\" is not an outcome");
  r.outcome = *o;
  r.status = text(e, key::kStatus, index);
  r.line = text(e, key::kLine, index);
  return r;
}

ResolvingPowerRecord read_resolving_power(const json& p, std::size_t index) {
  const std::string where = path_of(index, key::kResolvingPower);
  if (!p.is_object()) throw RecordError(where + ": must be an object");
  return {text(p, key::kSummary, index), texts_at(p, key::kBlindTo, where), texts_at(p, key::kUnseen, where)};
}

// The candidate's declaration as the case recorded it: "candidate" read back as candidate.json is
// read (outputs::declaration_from_json), its "defaulted" the keys the candidate left out.
std::optional<outputs::CandidateDeclaration> read_candidate(const json& c, const std::string& technique, std::size_t index) {
  const auto it = c.find(key::kCandidate);
  if (it == c.end() || it->is_null()) return std::nullopt;
  const std::string where = path_of(index, key::kCandidate);
  if (!it->is_object()) throw RecordError(where + ": must be an object, not " + it->dump());
  json declared = *it;
  const std::vector<std::string> defaulted = texts_at(declared, key::kDefaulted, where);
  declared.erase(key::kDefaulted);
  try {
    outputs::CandidateDeclaration d = outputs::declaration_from_json(declared, technique, where);
    d.defaulted = defaulted;
    return d;
  } catch (const outputs::InputError& e) {
    throw RecordError(e.what());
  }
}

}  // namespace

std::string ExpectationRecord::expected_by() const {
  return (status.empty() ? std::string("green") : status) + (line.empty() ? "" : " at " + line);
}

CaseRecord read_case(const json& c, std::size_t index) {
  if (!c.is_object()) throw RecordError("cases[" + std::to_string(index) + "]: must be an object");
  CaseRecord r;
  for (const char* required : {key::kScene, key::kTechnique, key::kStatus})
    if (!c.contains(required)) throw RecordError(path_of(index, required) + ": missing");
  r.scene = text(c, key::kScene, index);
  r.technique = text(c, key::kTechnique, index);
  r.status = detail::status_at(c, key::kStatus, where_of(index));
  for (const TextKey& t : kTextKeys) r.*t.field = text(c, t.name, index, r.*t.field);
  for (const NumberKey& n : kNumberKeys) r.*n.field = number(c, n.name, index, r.*n.field);
  if (c.contains(key::kHost)) r.host = text(c, key::kHost, index);
  r.notes = texts_at(c, key::kNotes, where_of(index));
  if (c.contains(key::kShard)) r.shard = count(c, key::kShard, index);
  if (c.contains(key::kExpectedFromHeight)) r.expected_from_height = count(c, key::kExpectedFromHeight, index);
  if (const auto e = c.find(key::kExpectation); e != c.end()) r.expectation = read_expectation(*e, index);
  if (const auto p = c.find(key::kResolvingPower); p != c.end()) r.resolving_power = read_resolving_power(*p, index);
  read_comparison(c, index, r);
  r.lights = read_lights(c, index);
  r.shaded = image(c, key::kShaded, where_of(index));
  r.reference_shaded = image(c, key::kReferenceShaded, where_of(index));
  r.candidate = read_candidate(c, r.technique, index);
  if (r.candidate) r.environment = r.candidate->environment;
  return r;
}

bool inside_report_folder(const std::string& rel) {
  const std::filesystem::path p(rel);
  if (rel.empty() || p.is_absolute()) return false;
  return std::none_of(p.begin(), p.end(), [](const std::filesystem::path& part) { return part == ".."; });
}

std::vector<CaseRecord> read_cases(const json& report) {
  std::vector<CaseRecord> out;
  if (!report.is_object() || !report.contains(key::kCases)) return out;
  const json& cases = report[key::kCases];
  if (!cases.is_array()) throw RecordError(std::string(key::kCases) + ": must be an array");
  out.reserve(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) out.push_back(read_case(cases[i], i));
  return out;
}

void write_case(const CaseRecord& r, json& k) {
  k[key::kScene] = r.scene;
  k[key::kTechnique] = r.technique;
  k[key::kStatus] = to_string(r.status);
  for (const TextKey& t : kTextKeys)
    if (writes(t.written, !(r.*t.field).empty())) k[t.name] = r.*t.field;
  for (const NumberKey& n : kNumberKeys)
    if (writes(n.written, r.*n.field != 0)) k[n.name] = r.*n.field;
  if (r.expected_from_height) k[key::kExpectedFromHeight] = r.expected_from_height;
  if (r.host) k[key::kHost] = *r.host;
  if (r.shard) k[key::kShard] = *r.shard;
  if (r.expectation) {
    json e = {{key::kOutcome, to_string(r.expectation->outcome)}};
    if (!r.expectation->status.empty()) e[key::kStatus] = r.expectation->status;
    if (!r.expectation->line.empty()) e[key::kLine] = r.expectation->line;
    k[key::kExpectation] = e;
  }
}

}  // namespace shadowref::record
