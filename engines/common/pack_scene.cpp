#include "pack_scene.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace engines {

namespace {

nlohmann::json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
}

const nlohmann::json& at(const nlohmann::json& j, const std::string& key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw std::runtime_error(where + ": no key '" + key + "'");
  return j.at(key);
}

Mat4 canonical(const nlohmann::json& m, const std::string& where) {
  const nlohmann::json& rows = at(m, "canonical", where);
  Mat4 out{};
  if (!rows.is_array() || rows.size() != 4) throw std::runtime_error(where + ".canonical: not 4 rows");
  for (std::size_t r = 0; r < 4; ++r) {
    if (!rows[r].is_array() || rows[r].size() != 4) throw std::runtime_error(where + ".canonical: not 4 columns");
    for (std::size_t c = 0; c < 4; ++c) out[r][c] = rows[r][c].get<double>();
  }
  return out;
}

}  // namespace

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k) m[r][c] += a[r][k] * b[k][c];
  return m;
}

std::vector<std::string> pack_scene_names(const std::filesystem::path& pack) {
  const std::filesystem::path file = pack / "manifest.json";
  const nlohmann::json manifest = read_json(file);
  std::vector<std::string> names;
  try {
    for (const nlohmann::json& s : at(manifest, "scenes", file.string())) names.push_back(s.at("name").get<std::string>());
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
  return names;
}

std::vector<std::string> select_scenes(const std::filesystem::path& pack, const std::string& wanted) {
  const std::vector<std::string> all = pack_scene_names(pack);
  if (wanted.empty()) return all;
  std::vector<std::string> picked;
  std::stringstream list(wanted);
  for (std::string name; std::getline(list, name, ',');) {
    bool found = false;
    for (const std::string& s : all) found = found || s == name;
    if (!found) throw std::runtime_error("no scene '" + name + "' in " + (pack / "manifest.json").string());
  }
  for (const std::string& s : all)
    if (("," + wanted + ",").find("," + s + ",") != std::string::npos) picked.push_back(s);
  return picked;
}

PackScene read_pack_scene(const std::filesystem::path& pack, const std::string& name) {
  PackScene s;
  s.name = name;
  s.dir = pack / name;
  const std::filesystem::path file = s.dir / "matrices.json";
  const std::string w = file.string();
  const nlohmann::json j = read_json(file);
  try {
    const nlohmann::json& res = at(j, "resolution", w);
    s.width = res.at(0).get<int>();
    s.height = res.at(1).get<int>();
    const nlohmann::json& cam = at(j, "camera", w);
    for (std::size_t i = 0; i < 3; ++i) s.camera_position[i] = at(cam, "position", w + ".camera").at(i).get<double>();
    s.near = at(cam, "near", w + ".camera").get<double>();
    const nlohmann::json& gl = at(at(j, "conventions", w), "gl", w + ".conventions");
    s.view = canonical(at(gl, "view", w + ".conventions.gl"), w + ".conventions.gl.view");
    s.projection_finite =
        canonical(at(gl, "projection_finite", w + ".conventions.gl"), w + ".conventions.gl.projection_finite");
    for (const nlohmann::json& l : at(j, "lights", w)) {
      PackLight light;
      light.type = l.at("type").get<std::string>();
      for (std::size_t i = 0; i < 4; ++i) light.homogeneous[i] = l.at("homogeneous").at(i).get<double>();
      light.mask_file = l.at("mask_file").get<std::string>();
      s.lights.push_back(light);
    }
    for (const nlohmann::json& o : at(j, "objects", w))
      s.objects.push_back({o.at("name").get<std::string>(), std::filesystem::absolute(s.dir / o.at("obj").get<std::string>())});
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(w + ": " + e.what());
  }
  if (s.width <= 0 || s.height <= 0) throw std::runtime_error(w + ": resolution is not positive");
  return s;
}

}  // namespace engines
