// gltf_writer.cpp — the pack's glTF 2.0 files (gltf_writer.hpp).
#include "shadowref/pack/gltf_writer.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "shadowref/convention.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/pack/matrix_json.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::pack {
namespace {

using nlohmann::json;

// RFC 4648 base64 with padding, for glTF's data: URIs.
std::string base64(const std::string& bytes) {
  static constexpr char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

// glTF 2.0 meshes appended into one embedded buffer: float positions and uint32 indices (both
// 4-byte elements, so every buffer view stays aligned without padding).
struct GltfMeshes {
  std::string buffer;
  json buffer_views = json::array();
  json accessors = json::array();
  json meshes = json::array();

  // Appends o's mesh with `material` (none when negative); returns the mesh index.
  int add(const scene::Object& o, int material = -1) {
    const std::size_t position_offset = buffer.size();
    Vec3<float> lo = o.mesh.positions.front(), hi = lo;
    for (const auto& p : o.mesh.positions) {
      buffer.append(reinterpret_cast<const char*>(p.data()), 3 * sizeof(float));
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const std::size_t index_offset = buffer.size();
    for (const auto& tri : o.mesh.triangles) buffer.append(reinterpret_cast<const char*>(tri.data()), 3 * sizeof(std::uint32_t));
    const std::size_t view = buffer_views.size();
    buffer_views.push_back({{"buffer", 0}, {"byteOffset", position_offset}, {"byteLength", index_offset - position_offset}, {"target", 34962}});
    buffer_views.push_back({{"buffer", 0}, {"byteOffset", index_offset}, {"byteLength", buffer.size() - index_offset}, {"target", 34963}});
    const std::size_t accessor = accessors.size();
    accessors.push_back({{"bufferView", view}, {"componentType", 5126}, {"count", o.mesh.positions.size()}, {"type", "VEC3"},
                         {"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}});
    accessors.push_back({{"bufferView", view + 1}, {"componentType", 5125}, {"count", 3 * o.mesh.triangles.size()}, {"type", "SCALAR"}});
    json primitive = {{"attributes", {{"POSITION", accessor}}}, {"indices", accessor + 1}, {"mode", 4}};
    if (material >= 0) primitive["material"] = material;
    meshes.push_back({{"name", o.name}, {"primitives", {primitive}}});
    return static_cast<int>(meshes.size() - 1);
  }

  void into(json& g) const {
    g["buffers"] = {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}};
    g["bufferViews"] = buffer_views;
    g["accessors"] = accessors;
    g["meshes"] = meshes;
  }
};

// The camera, exactly as matrices.json's gl convention has it: its glTF camera and its node.
void add_camera(const scene::Scene& s, json& g, json& nodes) {
  const scene::PreparedScene gl = scene::prepare_scene(s, kDefaultConvention);
  json perspective = {{"yfov", s.camera.fovy_deg * std::numbers::pi / 180.0},
                      {"aspectRatio", static_cast<double>(s.width) / static_cast<double>(s.height)},
                      {"znear", s.camera.near}};
  if (s.camera.far) perspective["zfar"] = *s.camera.far;
  g["cameras"] = {{{"name", "camera"}, {"type", "perspective"}, {"perspective", perspective}}};
  nodes.push_back({{"name", "camera"},
                   {"camera", 0},
                   {"matrix", column_major(gl.camera.view.inverse())},
                   {"extras",
                    {{"convention", "gl"},
                     {"resolution", {s.width, s.height}},
                     {"view", rows(gl.camera.view)},
                     {"projection", rows(gl.camera.projection)},
                     {"projection_finite", rows(gl.camera_finite_for_clamp.projection)},
                     {"layout", "canonical rows (column vectors, v' = M v), as matrices.json's gl convention"}}}});
}

// Light i as a KHR_lights_punctual light, and its node's transform (`at`).
json punctual_light(const scene::Scene& s, std::size_t i, Mat4<double>& at) {
  const scene::Light& l = s.lights[i];
  json light = {{"name", "light_" + std::to_string(i)}, {"color", {1.0, 1.0, 1.0}}, {"intensity", 1.0}};
  json extras = {{"index", i}, {"shadowref_type", scene::to_string(l.type)}, {"mask_file", outputs::mask_name(i, s.lights.size())}};
  at = Mat4<double>::Identity();
  switch (l.type) {
    case scene::LightType::Point:
      light["type"] = "point";
      at.block<3, 1>(0, 3) = l.position;
      break;
    case scene::LightType::Spot:
      light["type"] = "spot";
      light["spot"] = {{"innerConeAngle", 0.0}, {"outerConeAngle", l.cone_deg * std::numbers::pi / 180.0}};
      extras["note"] = "the cone shapes lighting only; the mask is the visibility of the position";
      at = node_facing(l.position, l.direction);
      break;
    case scene::LightType::Directional:
      light["type"] = "directional";
      at = node_facing(Vec3<double>::Zero(), -l.direction);
      extras["direction_toward_light"] = vec3(l.direction);
      break;
    case scene::LightType::Rect:
      light["type"] = "point";
      at.block<3, 1>(0, 3) = l.corner + 0.5 * (l.edge_u + l.edge_v);
      extras["corner"] = vec3(l.corner);
      extras["edge_u"] = vec3(l.edge_u);
      extras["edge_v"] = vec3(l.edge_v);
      extras["size"] = {{"edge_u_length", l.edge_u.norm()},
                        {"edge_v_length", l.edge_v.norm()},
                        {"equal_area_square_side", std::sqrt(l.edge_u.cross(l.edge_v).norm())}};
      extras["note"] = "a rect light: the point light at its centre is what hard techniques are judged with; soft ones use the "
                       "parallelogram (corner, edge_u, edge_v)";
      break;
  }
  light["extras"] = extras;
  return light;
}

}  // namespace

Mat4<double> node_facing(const Vec3<double>& position, const Vec3<double>& forward) {
  const Vec3<double> z = -forward.normalized();
  const Vec3<double> up = std::abs(z.y()) > 0.99 ? Vec3<double>(0, 0, -1) : Vec3<double>(0, 1, 0);
  const Vec3<double> x = up.cross(z).normalized();
  const Vec3<double> y = z.cross(x);
  Mat4<double> m = Mat4<double>::Identity();
  m.block<3, 1>(0, 0) = x;
  m.block<3, 1>(0, 1) = y;
  m.block<3, 1>(0, 2) = z;
  m.block<3, 1>(0, 3) = position;
  return m;
}

json object_gltf(const scene::Object& o) {
  GltfMeshes m;
  m.add(o);
  json g;
  g["asset"] = {{"version", "2.0"}, {"generator", "shadowref export"}};
  g["scene"] = 0;
  g["scenes"] = {{{"nodes", {0}}}};
  g["nodes"] = {{{"name", o.name}, {"mesh", 0}}};
  m.into(g);
  return g;
}

json scene_gltf(const scene::Scene& s) {
  GltfMeshes m;
  json g;
  g["asset"] = {{"version", "2.0"}, {"generator", "shadowref export"}};
  json nodes = json::array();
  json materials = json::array();
  for (const scene::Object& o : s.objects) {
    materials.push_back({{"name", o.name},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor", {o.color.x(), o.color.y(), o.color.z(), 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}});
    const int mesh = m.add(o, static_cast<int>(materials.size() - 1));
    nodes.push_back({{"name", o.name}, {"mesh", mesh}, {"extras", {{"receiver", o.receiver}, {"shape", o.shape}}}});
  }
  add_camera(s, g, nodes);
  json lights = json::array();
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    Mat4<double> at;
    lights.push_back(punctual_light(s, i, at));
    nodes.push_back({{"name", "light_" + std::to_string(i)},
                     {"matrix", column_major(at)},
                     {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
  }
  json scene_nodes = json::array();
  for (std::size_t n = 0; n < nodes.size(); ++n) scene_nodes.push_back(n);
  g["scene"] = 0;
  g["scenes"] = {{{"name", s.name}, {"nodes", scene_nodes}}};
  g["nodes"] = nodes;
  g["materials"] = materials;
  if (!lights.empty()) {
    g["extensionsUsed"] = {"KHR_lights_punctual"};
    g["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
  }
  m.into(g);
  return g;
}

}  // namespace shadowref::pack
