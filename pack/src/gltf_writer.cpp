// gltf_writer.cpp — the pack's glTF 2.0 files (gltf_writer.hpp).
#include "shadowref/pack/gltf_writer.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "shadowref/convention.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"
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

// glTF 2.0 meshes appended into one embedded buffer, flat: every triangle its own three vertices
// with its face normal (glTF asks a loader without normals for flat ones, and some smooth shared
// vertices instead), and a masked object's TEXCOORD_0 and COLOR_0 beside them. Every element is a
// 4-byte float or uint32, so every buffer view stays aligned without padding.
struct GltfMeshes {
  std::string buffer;
  json buffer_views = json::array();
  json accessors = json::array();
  json meshes = json::array();

  // Appends `values` (count elements of `type`, float, uint32 or uint16 components) as a buffer view
  // and its accessor; returns the accessor's index.
  template <class T>
  std::size_t append(const std::vector<T>& values, std::size_t count, const char* type, int component_type, int target,
                     json extra = json::object()) {
    const std::size_t offset = buffer.size();
    buffer.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    buffer_views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", buffer.size() - offset}});
    if (target) buffer_views.back()["target"] = target;  // 0: not vertex or index data (inverse bind matrices)
    json accessor = {{"bufferView", buffer_views.size() - 1}, {"componentType", component_type}, {"count", count}, {"type", type}};
    accessor.update(extra);
    accessors.push_back(accessor);
    return accessors.size() - 1;
  }

  // Appends o's mesh with `material` (none when negative); returns the mesh index. A skinned object
  // (scene/skin.hpp) is written in its bind pose with JOINTS_0 and WEIGHTS_0 (and bind-pose normals),
  // for the skin that scene_gltf writes beside it to pose.
  int add(const scene::Object& o, int material = -1) {
    std::vector<float> positions, normals, uvs, colours, weights;
    std::vector<std::uint16_t> joints;
    std::vector<std::uint32_t> indices;
    const auto vertex = [&](std::uint32_t k) { return o.skin ? o.skin->bind_positions[k] : o.mesh.positions[k]; };
    Vec3<float> lo = vertex(0), hi = lo;
    for (const auto& tri : o.mesh.triangles) {
      // The face normal as the renderer computes it: (v1 − v0) × (v2 − v0) in double, made unit.
      const Vec3<double> a = vertex(tri[0]).cast<double>(), b = vertex(tri[1]).cast<double>(), c = vertex(tri[2]).cast<double>();
      const Vec3<double> cr = (b - a).cross(c - a);
      const Vec3<float> n = cr.squaredNorm() > 0 ? Vec3<float>(cr.normalized().cast<float>()) : Vec3<float>(0, 1, 0);
      for (const std::uint32_t k : tri) {
        const Vec3<float> p = vertex(k);
        indices.push_back(static_cast<std::uint32_t>(positions.size() / 3));
        positions.insert(positions.end(), {p.x(), p.y(), p.z()});
        normals.insert(normals.end(), {n.x(), n.y(), n.z()});
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        if (o.alpha) {
          uvs.insert(uvs.end(), {o.alpha->uvs[k].x(), o.alpha->uvs[k].y()});
          colours.insert(colours.end(), {1.0f, 1.0f, 1.0f, o.alpha->vertex_alpha[k]});
        }
        if (o.skin) {
          joints.insert(joints.end(), o.skin->joint_indices[k].begin(), o.skin->joint_indices[k].end());
          weights.insert(weights.end(), o.skin->weights[k].begin(), o.skin->weights[k].end());
        }
      }
    }
    const std::size_t vertices = positions.size() / 3;
    json attributes;
    attributes["POSITION"] = append(positions, vertices, "VEC3", 5126, 34962,
                                    {{"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}});
    attributes["NORMAL"] = append(normals, vertices, "VEC3", 5126, 34962);
    if (o.alpha && !o.alpha->texture->file.empty()) attributes["TEXCOORD_0"] = append(uvs, vertices, "VEC2", 5126, 34962);
    if (o.alpha && o.alpha->has_vertex_alpha) attributes["COLOR_0"] = append(colours, vertices, "VEC4", 5126, 34962);
    if (o.skin) {  // unsigned short joints: 8 bytes a vertex, so the views stay 4-byte aligned
      attributes["JOINTS_0"] = append(joints, vertices, "VEC4", 5123, 34962);
      attributes["WEIGHTS_0"] = append(weights, vertices, "VEC4", 5126, 34962);
    }
    const std::size_t index_accessor = append(indices, indices.size(), "SCALAR", 5125, 34963);
    json primitive = {{"attributes", attributes}, {"indices", index_accessor}, {"mode", 4}};
    if (material >= 0) primitive["material"] = material;
    meshes.push_back({{"name", o.name}, {"primitives", {primitive}}});
    return static_cast<int>(meshes.size() - 1);
  }

  // o's skin: one root node per joint at the pose (`matrix`, its world transform: a joint of a
  // catalogue scene carries the object's transform) appended to `nodes`, and the skin (its inverse
  // bind matrices an accessor); returns the skin's index in `skins`.
  int add_skin(const scene::Object& o, json& nodes, json& skins) {
    json joint_nodes = json::array();
    std::vector<float> ibm;
    for (std::size_t j = 0; j < o.skin->joints.size(); ++j) {
      const scene::Skin::Joint& joint = o.skin->joints[j];
      joint_nodes.push_back(nodes.size());
      nodes.push_back({{"name", o.name + "_joint_" + std::to_string(j)}, {"matrix", column_major(joint.world)}});
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) ibm.push_back(static_cast<float>(joint.inverse_bind(r, c)));  // float in the file it came from
    }
    const std::size_t accessor = append(ibm, o.skin->joints.size(), "MAT4", 5126, 0);
    skins.push_back({{"name", o.name}, {"joints", joint_nodes}, {"inverseBindMatrices", accessor}});
    return static_cast<int>(skins.size() - 1);
  }

  void into(json& g) const {
    g["buffers"] = {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}};
    g["bufferViews"] = buffer_views;
    g["accessors"] = accessors;
    g["meshes"] = meshes;
  }
};

// A mask as the PNG a glTF loader reads it: grey + alpha, the grey white (the material's colour
// stays baseColorFactor's) and the alpha the mask's, whatever the scene's file held (a grey mask has
// no alpha channel, which glTF would read as opaque).
std::string mask_png(const scene::AlphaTexture& t) {
  outputs::Image8 image{t.width, t.height, 2, {}};
  image.pixels.reserve(2 * t.alpha.size());
  for (const std::uint8_t a : t.alpha) image.pixels.insert(image.pixels.end(), {std::uint8_t{255}, a});
  return outputs::encode_png(image);
}

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
      extras["samples"] = l.samples;  // the soft-shadow ground truth's samples × samples grid (read back by scene/gltf_scene.hpp)
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
  // The posed mesh (a skinned object's world-space triangles, as the OBJ beside it), not its skin.
  scene::Object posed = o;
  posed.skin.reset();
  m.add(posed);
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
  json images = json::array(), textures = json::array(), skins = json::array();
  const scene::PreparedScene prepared = scene::prepare_scene(s, kDefaultConvention);
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const scene::Object& o = s.objects[i];
    json material = {{"name", o.name},
                     {"pbrMetallicRoughness",
                      {{"baseColorFactor", {o.color.x(), o.color.y(), o.color.z(), 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
    // A masked object is a foliage card or a fence, authored double-sided as engines' alpha-tested
    // content is. Every other mesh is single-sided (glTF's default), an open one too: a single-sided
    // card still casts from both sides in the reference, so an engine whose depth pass culls its
    // lit front faces casts nothing of it, and shows that.
    if (o.alpha) material["doubleSided"] = true;
    if (o.alpha) {
      // glTF's own alpha test, the rule of scene/alpha_mask.hpp: alpha = baseColorFactor.a × the
      // texture's alpha × COLOR_0.a, opaque when >= alphaCutoff; NEAREST with REPEAT, TEXCOORD_0.
      material["alphaMode"] = "MASK";
      material["alphaCutoff"] = o.alpha->cutoff;
      if (!o.alpha->texture->file.empty()) {
        textures.push_back({{"sampler", 0}, {"source", images.size()}});
        images.push_back({{"name", o.name + "_mask"}, {"mimeType", "image/png"},
                          {"uri", "data:image/png;base64," + base64(mask_png(*o.alpha->texture))}});
        material["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", textures.size() - 1}, {"texCoord", 0}};
      }
    }
    materials.push_back(material);
    const int mesh = m.add(o, static_cast<int>(materials.size() - 1));
    nodes.push_back({{"name", o.name}, {"mesh", mesh}, {"extras", {{"receiver", o.receiver}, {"shape", o.shape}}}});
    // A skinned object's node at the origin (glTF applies only its joints' transforms), its joints after it.
    if (o.skin) {
      const std::size_t node = nodes.size() - 1;
      const int skin = m.add_skin(o, nodes, skins);
      nodes[node]["skin"] = skin;
    }
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
  // glTF's unit is the metre: a scene in another unit says which (scene.hpp, LengthUnit).
  g["scenes"] = {{{"name", s.name}, {"nodes", scene_nodes}}};
  if (s.units.metres != 1.0)
    g["scenes"][0]["extras"] = {{"units", std::string(s.units.symbol)}, {"metres_per_unit", s.units.metres}};
  g["nodes"] = nodes;
  g["materials"] = materials;
  if (!skins.empty()) g["skins"] = skins;
  if (!images.empty()) {
    // NEAREST (9728) both ways, REPEAT (10497) on both axes: the rule's texel.
    g["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9728}, {"wrapS", 10497}, {"wrapT", 10497}}};
    g["images"] = images;
    g["textures"] = textures;
  }
  if (!lights.empty()) {
    g["extensionsUsed"] = {"KHR_lights_punctual"};
    g["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
  }
  m.into(g);
  return g;
}

}  // namespace shadowref::pack
