// scene_files.cpp — one scene's files in the pack (scene_files.hpp).
#include "shadowref/pack/scene_files.hpp"

#include <cctype>
#include <fstream>
#include <limits>
#include <span>

#include "shadowref/light_fit.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/json_text.hpp"
#include "shadowref/pack/gltf_writer.hpp"
#include "shadowref/pack/matrices.hpp"
#include "shadowref/pack/obj_writer.hpp"

namespace shadowref::pack {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The scene file, and the mesh and mask files it names next to it (the same relative paths): a JSON
// scene's mesh files and masks, a .gltf scene's external buffers and images (not data: URIs).
void copy_scene_file(const fs::path& f, const fs::path& scenes) {
  fs::copy_file(f, scenes / f.filename(), fs::copy_options::overwrite_existing);
  std::ifstream in(f);
  const json sj = json::parse(in, nullptr, false);
  for (const char* key : {"buffers", "images"})
    if (sj.is_object() && sj.contains(key) && sj[key].is_array())
      for (const auto& b : sj[key]) {
        if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
        const fs::path rel = b["uri"].get<std::string>();
        std::error_code ec;
        if (rel.string().rfind("data:", 0) == 0 || !fs::is_regular_file(f.parent_path() / rel, ec)) continue;
        fs::create_directories((scenes / rel).parent_path());
        fs::copy_file(f.parent_path() / rel, scenes / rel, fs::copy_options::overwrite_existing);
      }
  if (sj.is_object() && sj.contains("objects"))
    for (const auto& o : sj["objects"])
      for (const json* file : {o.contains("shape") && o["shape"].contains("file") ? &o["shape"]["file"] : nullptr,
                               o.contains("alpha_texture") ? &o["alpha_texture"] : nullptr}) {
        if (!file) continue;
        const fs::path rel = file->get<std::string>();
        fs::create_directories((scenes / rel).parent_path());
        fs::copy_file(f.parent_path() / rel, scenes / rel, fs::copy_options::overwrite_existing);
      }
}

}  // namespace

std::string safe_name(std::string s) {
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
  return s;
}

void write_scene_files(const scene::Scene& s, const fs::path& scene_file, const fs::path& out) {
  const fs::path dir = out / s.name;
  fs::create_directories(dir / "meshes");
  copy_scene_file(scene_file, out / "scenes");
  json objects = json::array();
  for (const scene::Object& o : s.objects) {
    const std::string n = safe_name(o.name);
    outputs::write_file_atomically(dir / "meshes" / (n + ".obj"), obj_text(o));
    outputs::write_file_atomically(dir / "meshes" / (n + ".gltf"), outputs::json_text(object_gltf(o)) + "\n");
    objects.push_back({{"name", o.name}, {"obj", "meshes/" + n + ".obj"}, {"gltf", "meshes/" + n + ".gltf"},
                       {"receiver", o.receiver}, {"color", {o.color.x(), o.color.y(), o.color.z()}}});
  }
  outputs::write_file_atomically(dir / "scene.gltf", outputs::json_text(scene_gltf(s)) + "\n");
  json m = matrices_json(s);
  m["objects"] = objects;
  m["scene_gltf"] = "scene.gltf";
  outputs::write_file_atomically(dir / "matrices.json", outputs::json_text(m, 2) + "\n");
}

namespace {

// Per light, the surface nearest to its point (a rect light's centre; null for a directional
// light): {"distance": in the scene's units, "object": its name}.
json light_clearance(const scene::Scene& s) {
  json out = json::array();
  for (const scene::Light& l : s.lights) {
    if (l.type == scene::LightType::Directional) {
      out.push_back(nullptr);
      continue;
    }
    const Vec3<double> at = scene::homogeneous(l).head<3>();
    double nearest = std::numeric_limits<double>::infinity();
    std::string object;
    for (const scene::Object& o : s.objects) {
      const TriangleMesh<float>* m = &o.mesh;
      const double d = nearest_triangle_distance(at, std::span<const TriangleMesh<float>* const>(&m, 1));
      if (d < nearest) nearest = d, object = o.name;
    }
    out.push_back({{"distance", nearest}, {"object", object}});
  }
  return out;
}

}  // namespace

json manifest_head() {
  json manifest;
  manifest["tool"] = "shadowref export";
  manifest["mask_values"] = {{"lit", outputs::kMaskLit}, {"shadowed", outputs::kMaskShadowed}, {"no_surface", outputs::kMaskNoSurface}};
  manifest["scenes"] = json::array();
  return manifest;
}

json manifest_entry(const scene::Scene& s, const fs::path& scene_file) {
  json expect = json::object();
  for (const auto& [t, e] : s.expect) {
    expect[t] = !e.pass ? json{{"result", "fail"}, {"why", e.why}}
                : e.warn ? json{{"result", "warn"}, {"why", e.why}}
                         : json{{"result", "pass"}};
    if (e.from_height) expect[t]["from_height"] = e.from_height;
  }
  const auto [lo, hi] = scene::bounds(s);
  return {{"name", s.name},
          {"description", s.description},
          {"resolution", {s.width, s.height}},
          {"lights", s.lights.size()},
          {"units", {{"symbol", s.units.symbol}, {"name", s.units.name}, {"metres", s.units.metres}}},
          {"size", (hi - lo).norm()},
          {"light_clearance", light_clearance(s)},
          {"scene_file", "scenes/" + scene_file.filename().string()},
          {"expect", expect}};
}

}  // namespace shadowref::pack
