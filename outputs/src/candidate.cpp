// candidate.cpp — reading and writing candidate.json (candidate.hpp), with nlohmann-json.
#include "shadowref/outputs/candidate.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>

#include "shadowref/cascades.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::outputs {

std::optional<DepthFaces> depth_faces_from(std::string_view name) {
  for (const DepthFaces f : {DepthFaces::Front, DepthFaces::Back, DepthFaces::Both})
    if (name == to_string(f)) return f;
  return std::nullopt;
}

const char* to_string(DepthFaces f) {
  switch (f) {
    case DepthFaces::Front: return "front";
    case DepthFaces::Back: return "back";
    case DepthFaces::Both: return "both";
  }
  return "?";
}

const char* to_string(LightViews v) {
  switch (v) {
    case LightViews::Own: return "own";
    case LightViews::Pack: return "pack";
    case LightViews::Declared: return "declared";
  }
  return "?";
}

const char* to_string(StoredDepth d) { return d == StoredDepth::Distance ? "distance" : "window"; }

const char* to_string(Sampling s) { return s == Sampling::Random ? "random" : "grid"; }

CandidateDeclaration default_declaration(const std::string& technique) {
  CandidateDeclaration d;
  d.technique = technique;
  const TechniqueName* t = find_technique_name(technique);
  d.filter_radius_texels = t && (t->family == TechniqueFamily::ShadowMapPcf || t->family == TechniqueFamily::SoftShadow) ? 1.0 : 0.0;
  d.defaulted.assign(kCandidateKeys.begin(), kCandidateKeys.end());
  return d;
}

namespace {

using Json = nlohmann::json;
using Bad = std::function<InputError(const std::string&)>;

// The keys a `lights` entry may override: everything that can differ between two lights of one render.
bool per_light_key(const std::string& key) {
  return key != "producer" && key != "version" && key != "technique" && key != "convention" && key != "settings" &&
         key != "environment" && key != "lights";
}

// 16 finite numbers, column-major.
std::array<double, 16> read_matrix(const Json& m, const std::string& key, const Bad& bad) {
  if (!m.is_array() || m.size() != 16) throw bad(key + ": must be an array of 16 numbers (column-major)");
  std::array<double, 16> out{};
  for (std::size_t i = 0; i < 16; ++i) {
    if (!m[i].is_number() || !std::isfinite(m[i].get<double>())) throw bad(key + "[" + std::to_string(i) + "]: must be a finite number");
    out[i] = m[i].get<double>();
  }
  return out;
}

// "views": 1 to kMaxDeclaredViews objects {"view": [16], "projection": [16]}, each whose
// projection × view maps scene space onto clip space invertibly (a texel's ray must exist).
std::vector<DeclaredView> read_views(const Json& v, const std::string& key, const Bad& bad) {
  if (!v.is_array() || v.empty() || v.size() > kMaxDeclaredViews)
    throw bad(key + ": must be an array of 1 to " + std::to_string(kMaxDeclaredViews) +
              " objects {\"view\": [16 numbers], \"projection\": [16 numbers]}");
  std::vector<DeclaredView> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string at = key + "[" + std::to_string(i) + "]";
    if (!v[i].is_object() || v[i].size() != 2 || !v[i].contains("view") || !v[i].contains("projection"))
      throw bad(at + ": must be {\"view\": [16 numbers], \"projection\": [16 numbers]} and nothing else");
    DeclaredView d;
    d.view = read_matrix(v[i]["view"], at + ".view", bad);
    d.projection = read_matrix(v[i]["projection"], at + ".projection", bad);
    const Eigen::Map<const Eigen::Matrix4d> view(d.view.data()), projection(d.projection.data());
    const double det = (projection * view).determinant();
    if (!std::isfinite(det) || det == 0) throw bad(at + ": projection x view is singular (no texel has a ray)");
    out.push_back(d);
  }
  return out;
}

// "cascade_splits": 2 to kMaxDeclaredViews + 1 increasing camera depths, the first >= 0.
std::vector<double> read_splits(const Json& v, const std::string& key, const Bad& bad) {
  if (!v.is_array() || v.size() < 2 || v.size() > kMaxDeclaredViews + 1)
    throw bad(key + ": must be an array of 2 to " + std::to_string(kMaxDeclaredViews + 1) + " camera depths");
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()) || v[i].get<double>() < 0 ||
        (i > 0 && !(v[i].get<double>() > out.back())))
      throw bad(key + "[" + std::to_string(i) + "]: must be a finite depth >= 0, larger than the one before");
    out.push_back(v[i].get<double>());
  }
  return out;
}

// Reads the keys of object `j` into `d` (`where` prefixes messages: "" or "lights[1].").
void read_keys(const Json& j, CandidateDeclaration& d, std::set<std::string>& given, const Bad& bad,
               const std::string& where, const std::string& technique) {
  const auto string_key = [&](const char* key, std::string& out) {
    if (!j.contains(key)) return;
    if (!j[key].is_string()) throw bad(where + key + ": must be a string");
    out = j[key].get<std::string>();
    if (out.size() > 200) throw bad(where + key + ": longer than 200 characters");
    given.insert(key);
  };
  const auto number_key = [&](const char* key, double& out, double hi) {
    if (!j.contains(key)) return;
    if (!j[key].is_number()) throw bad(where + key + ": must be a number");
    const double v = j[key].get<double>();
    if (!std::isfinite(v) || v < 0 || v > hi) throw bad(where + key + ": must be in [0, " + std::to_string(hi) + "]");
    out = v;
    given.insert(key);
  };
  const auto integer_key = [&](const char* key, int& out, long long lo, long long hi, const std::string& range) {
    if (!j.contains(key)) return;
    if (!j[key].is_number_integer()) throw bad(where + key + ": must be an integer");
    const auto v = j[key].get<long long>();
    if (v < lo || v > hi) throw bad(where + key + ": " + range);
    out = static_cast<int>(v);
    given.insert(key);
  };
  string_key("producer", d.producer);
  string_key("version", d.version);
  string_key("technique", d.technique);
  string_key("convention", d.convention);
  if (j.contains("shadow_map_size")) {
    if (!j["shadow_map_size"].is_number_integer()) throw bad(where + "shadow_map_size: must be an integer");
    const auto v = j["shadow_map_size"].get<long long>();
    if (const std::string p = shadow_map_size_problem(v); !p.empty()) throw bad(where + "shadow_map_size: " + p);
    d.shadow_map_size = static_cast<int>(v);
    d.atlas_tile_size = d.atlas_guard_band = 0;  // a light's own size replaces the top level's tile
    given.insert("shadow_map_size");
  }
  if (j.contains("atlas_tile")) {
    const std::string key = where + "atlas_tile";
    const Json& a = j["atlas_tile"];
    if (j.contains("shadow_map_size"))
      throw bad(key + ": give the tile or shadow_map_size, not both (a tile's map size is its size less its guard bands)");
    if (!a.is_object() || !a.contains("size") || !a["size"].is_number_integer() ||
        (a.contains("guard_band") && !a["guard_band"].is_number_integer()) || a.size() != (a.contains("guard_band") ? 2u : 1u))
      throw bad(key + ": must be {\"size\": texels, \"guard_band\": texels per side} (integers)");
    const auto size = a["size"].get<long long>(), guard = a.value("guard_band", 0LL);
    if (guard < 0 || size < 0 || size - 2 * guard < kMinShadowMapSize || size > kMaxShadowMapSize)
      throw bad(key + ": the size less twice the guard band must be in [" + std::to_string(kMinShadowMapSize) + ", " +
                std::to_string(kMaxShadowMapSize) + "] (got " + std::to_string(size) + " - 2 x " + std::to_string(guard) + ")");
    d.atlas_tile_size = static_cast<int>(size);
    d.atlas_guard_band = static_cast<int>(guard);
    d.shadow_map_size = static_cast<int>(size - 2 * guard);
    given.insert("atlas_tile");
    given.insert("shadow_map_size");
  }
  if (where.empty()) {
    if (!given.count("technique") || d.technique.empty()) d.technique = technique;
    // A known technique's family decides the filter default before the file may override it.
    d.filter_radius_texels = default_declaration(d.technique).filter_radius_texels;
  }
  number_key("filter_radius_texels", d.filter_radius_texels, 64.0);
  number_key("slope_bias_texels", d.slope_bias_texels, 64.0);
  number_key("constant_bias", d.constant_bias, 1e6);
  if (j.contains("light_views")) {
    const Json& v = j["light_views"];
    const LightViews all[] = {LightViews::Own, LightViews::Pack, LightViews::Declared};
    const auto it = std::find_if(std::begin(all), std::end(all), [&](LightViews l) { return v.is_string() && v == to_string(l); });
    if (it == std::end(all)) throw bad(where + "light_views: must be \"own\", \"pack\" or \"declared\"");
    d.light_views = *it;
    given.insert("light_views");
  }
  if (j.contains("views")) {
    d.views = read_views(j["views"], where + "views", bad);
    given.insert("views");
  }
  if (j.contains("cascade_splits")) {
    d.cascade_splits = read_splits(j["cascade_splits"], where + "cascade_splits", bad);
    given.insert("cascade_splits");
  }
  if (j.contains("cascade_blend")) {
    const Json& v = j["cascade_blend"];
    if (!v.is_number() || !(v.get<double>() >= 0 && v.get<double>() < 1))
      throw bad(where + "cascade_blend: must be a number in [0, 1) (the blended share of each cascade's depth range)");
    d.cascade_blend = v.get<double>();
    given.insert("cascade_blend");
  }
  if ((!d.views.empty() || !d.cascade_splits.empty()) && d.light_views != LightViews::Declared)
    throw bad(where + (d.views.empty() ? "cascade_splits" : "views") + ": given, but light_views is not \"declared\"");
  integer_key("cascades", d.cascades, 0, kMaxCascades,
              "must be in [0, " + std::to_string(kMaxCascades) + "] (0: the pack's count)");
  integer_key("light_taps", d.light_taps, 1, kMaxLightTaps, "must be in [1, " + std::to_string(kMaxLightTaps) + "]");
  if (j.contains("sampling")) {
    const Json& v = j["sampling"];
    if (!v.is_string() || (v != "grid" && v != "random")) throw bad(where + "sampling: must be \"grid\" or \"random\"");
    d.sampling = v == "random" ? Sampling::Random : Sampling::Grid;
    given.insert("sampling");
  }
  number_key("normal_offset", d.normal_offset, 1e6);
  number_key("normal_offset_texels", d.normal_offset_texels, 64.0);
  number_key("depth_bias", d.depth_bias, 1.0);
  if (j.contains("depth_faces")) {
    const Json& f = j["depth_faces"];
    const std::optional<DepthFaces> faces = f.is_string() ? depth_faces_from(f.get<std::string>()) : std::nullopt;
    if (!faces) throw bad(where + "depth_faces: must be \"front\", \"back\" or \"both\"");
    d.depth_faces = *faces;
    given.insert("depth_faces");
  }
  if (j.contains("depth")) {
    const Json& v = j["depth"];
    if (!v.is_string() || (v != "window" && v != "distance")) throw bad(where + "depth: must be \"window\" or \"distance\"");
    d.depth = v == "distance" ? StoredDepth::Distance : StoredDepth::Window;
    given.insert("depth");
  }
  number_key("depth_range", d.depth_range, 1e9);
  if (d.depth == StoredDepth::Distance && d.depth_bias > 0 && !(d.depth_range > 0))
    throw bad(where + "depth_range: a \"distance\" map's depth_bias is in units of its range: give depth_range (world units, far - near)");
  if (j.contains("environment")) {
    const Json& e = j["environment"];
    if (!e.is_object()) throw bad(where + "environment: must be a JSON object of strings (api, adapter, browser, engine)");
    for (const auto& item : e.items())
      if (std::find(kEnvironmentKeys.begin(), kEnvironmentKeys.end(), item.key()) == kEnvironmentKeys.end())
        throw bad(where + "environment." + item.key() + ": unknown key (expected api, adapter, browser or engine)");
    for (const char* key : kEnvironmentKeys) {
      if (!e.contains(key)) continue;
      if (!e[key].is_string() || e[key].get<std::string>().empty() || e[key].get<std::string>().size() > 256)
        throw bad(where + "environment." + key + ": must be a non-empty string of at most 256 bytes");
      d.environment.emplace_back(key, e[key].get<std::string>());
    }
    given.insert("environment");
  }
  if (j.contains("settings")) {
    if (!j["settings"].is_object()) throw bad(where + "settings: must be a JSON object");
    d.settings_json = j["settings"].dump();
    if (d.settings_json.size() > 65536) throw bad(where + "settings: larger than 64 KiB");
    given.insert("settings");
  }
}

}  // namespace

std::string environment_text(const Environment& environment) {
  std::string out;
  for (const auto& [k, v] : environment) out += (out.empty() ? "" : " · ") + k + " " + v;
  return out;
}

const CandidateDeclaration& CandidateDeclaration::for_light(std::size_t light) const {
  return light < lights.size() ? lights[light] : *this;
}

CandidateDeclaration declaration_from_json(const nlohmann::json& j, const std::string& technique, const std::string& where) {
  const Bad bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, where + ": " + what); };
  CandidateDeclaration d = default_declaration(technique);
  if (!j.is_object()) throw bad("must be a JSON object");
  const std::set<std::string> known(kCandidateKeys.begin(), kCandidateKeys.end());
  for (const auto& item : j.items())
    if (!known.count(item.key()))
      throw bad(item.key() + ": unknown key (an engine's own settings go in the \"settings\" object, which is recorded and never judged)");
  std::set<std::string> given;
  read_keys(j, d, given, bad, "", technique);
  if (j.contains("lights")) {
    const Json& lights = j["lights"];
    if (!lights.is_array()) throw bad("lights: must be an array of objects, one per light in the pack's order");
    if (lights.size() > kMaxDeclaredLights) throw bad("lights: more than " + std::to_string(kMaxDeclaredLights) + " entries");
    given.insert("lights");
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const std::string at = "lights[" + std::to_string(i) + "].";
      if (!lights[i].is_object()) throw bad(at.substr(0, at.size() - 1) + ": must be a JSON object");
      for (const auto& item : lights[i].items())
        if (!known.count(item.key()) || !per_light_key(item.key()))
          throw bad(at + item.key() + (known.count(item.key()) ? ": not a per-light key (give it at the top level)"
                                                               : ": unknown key (an engine's own settings go in the "
                                                                 "top-level \"settings\" object)"));
      CandidateDeclaration light = d;
      light.lights.clear();
      std::set<std::string> light_given;
      read_keys(lights[i], light, light_given, bad, at, technique);
      d.lights.push_back(std::move(light));
    }
  }
  d.defaulted.clear();
  for (const char* k : kCandidateKeys)
    if (!given.count(k)) d.defaulted.push_back(k);
  for (CandidateDeclaration& light : d.lights) light.defaulted = d.defaulted;
  return d;
}

CandidateDeclaration read_declaration(const std::filesystem::path& dir, const std::string& technique) {
  const std::filesystem::path file = dir / kCandidateFile;
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return default_declaration(technique);
  const auto bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, file.string() + ": " + what); };
  std::ifstream in(file, std::ios::binary);
  if (!in) throw bad("cannot read");
  const Json j = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw bad("not valid JSON");
  return declaration_from_json(j, technique, file.string());
}

std::string declaration_text(const CandidateDeclaration& d) {
  nlohmann::json j;
  j["producer"] = d.producer;
  j["version"] = d.version;
  j["technique"] = d.technique;
  j["convention"] = d.convention;
  if (d.atlas_tile_size > 0)
    j["atlas_tile"] = {{"size", d.atlas_tile_size}, {"guard_band", d.atlas_guard_band}};
  else
    j["shadow_map_size"] = d.shadow_map_size;
  j["filter_radius_texels"] = d.filter_radius_texels;
  j["slope_bias_texels"] = d.slope_bias_texels;
  j["constant_bias"] = d.constant_bias;
  j["light_views"] = to_string(d.light_views);
  if (!d.views.empty()) {
    nlohmann::json views = nlohmann::json::array();
    for (const DeclaredView& v : d.views) views.push_back({{"view", v.view}, {"projection", v.projection}});
    j["views"] = views;
  }
  if (!d.cascade_splits.empty()) j["cascade_splits"] = d.cascade_splits;
  j["cascade_blend"] = d.cascade_blend;
  j["cascades"] = d.cascades;
  j["light_taps"] = d.light_taps;
  j["sampling"] = to_string(d.sampling);
  j["normal_offset"] = d.normal_offset;
  j["normal_offset_texels"] = d.normal_offset_texels;
  j["depth_bias"] = d.depth_bias;
  j["depth_faces"] = to_string(d.depth_faces);
  j["depth"] = to_string(d.depth);
  j["depth_range"] = d.depth_range;
  if (!d.environment.empty()) {
    nlohmann::json env = nlohmann::json::object();
    for (const auto& [k, v] : d.environment) env[k] = v;
    j["environment"] = env;
  }
  j["settings"] = nlohmann::json::parse(d.settings_json);
  // Each light's entry: only the keys that differ from the top level.
  if (!d.lights.empty()) {
    CandidateDeclaration top_alone = d;
    top_alone.lights.clear();
    const nlohmann::json top = nlohmann::json::parse(declaration_text(top_alone));
    nlohmann::json lights = nlohmann::json::array();
    for (const CandidateDeclaration& l : d.lights) {
      CandidateDeclaration alone = l;
      alone.lights.clear();
      nlohmann::json entry = nlohmann::json::object();
      const nlohmann::json all = nlohmann::json::parse(declaration_text(alone));  // alive through the loop
      for (const auto& item : all.items())
        if (per_light_key(item.key()) && top.value(item.key(), nlohmann::json()) != item.value()) entry[item.key()] = item.value();
      lights.push_back(entry);
    }
    j["lights"] = lights;
  }
  return json_text(j, 2);
}

void write_declaration(const CandidateDeclaration& d, const std::filesystem::path& dir) {
  write_file_atomically(dir / kCandidateFile, declaration_text(d) + "\n");
}

}  // namespace shadowref::outputs
