// candidate.cpp — reading and writing candidate.json (candidate.hpp), with nlohmann-json.
#include "shadowref/outputs/candidate.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <set>

#include "shadowref/cascades.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::outputs {

const char* to_string(DepthFaces f) {
  switch (f) {
    case DepthFaces::Front: return "front";
    case DepthFaces::Back: return "back";
    case DepthFaces::Both: return "both";
  }
  return "?";
}

CandidateDeclaration default_declaration(const std::string& technique) {
  CandidateDeclaration d;
  d.technique = technique;
  const TechniqueName* t = find_technique_name(technique);
  d.filter_radius_texels = t && (t->family == TechniqueFamily::ShadowMapPcf || t->family == TechniqueFamily::SoftShadow) ? 1.0 : 0.0;
  d.defaulted.assign(kCandidateKeys.begin(), kCandidateKeys.end());
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
  const std::set<std::string> known(kCandidateKeys.begin(), kCandidateKeys.end());
  for (const auto& item : j.items())
    if (!known.count(item.key()))
      throw bad(item.key() + ": unknown key (an engine's own settings go in the \"settings\" object, which is recorded and never judged)");
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
    if (const std::string p = shadow_map_size_problem(v); !p.empty()) throw bad("shadow_map_size: " + p);
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
  number_key("normal_offset", d.normal_offset, 1e6);
  number_key("normal_offset_texels", d.normal_offset_texels, 64.0);
  number_key("depth_bias", d.depth_bias, 1.0);
  if (j.contains("depth_faces")) {
    const nlohmann::json& f = j["depth_faces"];
    if (!f.is_string() || (f != "front" && f != "back" && f != "both")) throw bad("depth_faces: must be \"front\", \"back\" or \"both\"");
    d.depth_faces = f == "front" ? DepthFaces::Front : f == "back" ? DepthFaces::Back : DepthFaces::Both;
    given.insert("depth_faces");
  }
  if (j.contains("settings")) {
    if (!j["settings"].is_object()) throw bad("settings: must be a JSON object");
    d.settings_json = j["settings"].dump();
    if (d.settings_json.size() > 65536) throw bad("settings: larger than 64 KiB");
    given.insert("settings");
  }
  d.defaulted.clear();
  for (const char* k : kCandidateKeys)
    if (!given.count(k)) d.defaulted.push_back(k);
  return d;
}

std::string declaration_text(const CandidateDeclaration& d) {
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
  j["normal_offset"] = d.normal_offset;
  j["normal_offset_texels"] = d.normal_offset_texels;
  j["depth_bias"] = d.depth_bias;
  j["depth_faces"] = to_string(d.depth_faces);
  j["settings"] = nlohmann::json::parse(d.settings_json);
  return json_text(j, 2);
}

void write_declaration(const CandidateDeclaration& d, const std::filesystem::path& dir) {
  write_file_atomically(dir / kCandidateFile, declaration_text(d) + "\n");
}

}  // namespace shadowref::outputs
