// candidate.cpp — reading and writing candidate.json (candidate.hpp), with nlohmann-json.
#include "shadowref/outputs/candidate.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <set>

#include "shadowref/cascades.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::outputs {

CandidateDeclaration default_declaration(const std::string& technique) {
  CandidateDeclaration d;
  d.technique = technique;
  const TechniqueName* t = find_technique_name(technique);
  d.filter_radius_texels = t && (t->family == TechniqueFamily::ShadowMapPcf || t->family == TechniqueFamily::SoftShadow) ? 1.0 : 0.0;
  d.defaulted = {"producer", "version", "technique", "convention", "shadow_map_size", "filter_radius_texels",
                 "slope_bias_texels", "constant_bias", "light_views", "cascades"};
  return d;
}

CandidateDeclaration read_declaration(const std::filesystem::path& dir, const std::string& technique) {
  const std::filesystem::path file = dir / kCandidateFile;
  CandidateDeclaration d = default_declaration(technique);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return d;
  const auto bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, file.string() + ": " + what); };
  std::ifstream in(file, std::ios::binary);
  if (!in) throw bad("cannot read");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw bad("not valid JSON");
  if (!j.is_object()) throw bad("must be a JSON object");
  static const std::set<std::string> known{"producer", "version", "technique", "convention", "shadow_map_size",
                                           "filter_radius_texels", "slope_bias_texels", "constant_bias", "light_views",
                                           "cascades", "light_taps"};
  for (const auto& item : j.items())
    if (!known.count(item.key())) throw bad(item.key() + ": unknown key");
  std::set<std::string> given;
  const auto string_key = [&](const char* key, std::string& out) {
    if (!j.contains(key)) return;
    if (!j[key].is_string()) throw bad(std::string(key) + ": must be a string");
    out = j[key].get<std::string>();
    if (out.size() > 200) throw bad(std::string(key) + ": longer than 200 characters");
    given.insert(key);
  };
  const auto number_key = [&](const char* key, double& out, double hi) {
    if (!j.contains(key)) return;
    if (!j[key].is_number()) throw bad(std::string(key) + ": must be a number");
    const double v = j[key].get<double>();
    if (!std::isfinite(v) || v < 0 || v > hi) throw bad(std::string(key) + ": must be in [0, " + std::to_string(hi) + "]");
    out = v;
    given.insert(key);
  };
  string_key("producer", d.producer);
  string_key("version", d.version);
  string_key("technique", d.technique);
  string_key("convention", d.convention);
  if (j.contains("shadow_map_size")) {
    if (!j["shadow_map_size"].is_number_integer()) throw bad("shadow_map_size: must be an integer");
    const auto v = j["shadow_map_size"].get<long long>();
    if (v != 0 && (v < 16 || v > 16384)) throw bad("shadow_map_size: must be 0 (automatic) or in [16, 16384]");
    d.shadow_map_size = static_cast<int>(v);
    given.insert("shadow_map_size");
  }
  if (!given.count("technique") || d.technique.empty()) d.technique = technique;
  // A known technique's family decides the filter default before the file may override it.
  d.filter_radius_texels = default_declaration(d.technique).filter_radius_texels;
  number_key("filter_radius_texels", d.filter_radius_texels, 64.0);
  number_key("slope_bias_texels", d.slope_bias_texels, 64.0);
  number_key("constant_bias", d.constant_bias, 1e6);
  if (j.contains("light_views")) {
    if (!j["light_views"].is_string() || (j["light_views"] != "pack" && j["light_views"] != "own"))
      throw bad("light_views: must be \"pack\" or \"own\"");
    d.light_views_from_pack = j["light_views"] == "pack";
    given.insert("light_views");
  }
  if (j.contains("cascades")) {
    if (!j["cascades"].is_number_integer()) throw bad("cascades: must be an integer");
    const auto v = j["cascades"].get<long long>();
    if (v < 0 || v > kMaxCascades)
      throw bad("cascades: must be in [0, " + std::to_string(kMaxCascades) + "] (0: the pack's count)");
    d.cascades = static_cast<int>(v);
    given.insert("cascades");
  }
  if (j.contains("light_taps")) {
    if (!j["light_taps"].is_number_integer()) throw bad("light_taps: must be an integer");
    const auto v = j["light_taps"].get<long long>();
    if (v < 1 || v > kMaxLightTaps) throw bad("light_taps: must be in [1, " + std::to_string(kMaxLightTaps) + "]");
    d.light_taps = static_cast<int>(v);
    given.insert("light_taps");
  }
  d.defaulted.clear();
  for (const std::string& k : known)
    if (!given.count(k)) d.defaulted.push_back(k);
  return d;
}

void write_declaration(const CandidateDeclaration& d, const std::filesystem::path& dir) {
  nlohmann::json j;
  j["producer"] = d.producer;
  j["version"] = d.version;
  j["technique"] = d.technique;
  j["convention"] = d.convention;
  j["shadow_map_size"] = d.shadow_map_size;
  j["filter_radius_texels"] = d.filter_radius_texels;
  j["slope_bias_texels"] = d.slope_bias_texels;
  j["constant_bias"] = d.constant_bias;
  j["light_views"] = d.light_views_from_pack ? "pack" : "own";
  j["cascades"] = d.cascades;
  j["light_taps"] = d.light_taps;
  std::ofstream f(dir / kCandidateFile, std::ios::binary);
  f << json_text(j, 2) << "\n";
  if (!f) throw FileError((dir / kCandidateFile).string() + ": cannot write");
}

}  // namespace shadowref::outputs
