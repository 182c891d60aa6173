// gltf_scene.cpp — an engine team's glTF 2.0 scene → Scene (gltf_scene.hpp). The file is opened
// by tinygltf through gltf_model.hpp (confined, nothing decoded); this file walks the scene once,
// collecting the camera, light and mesh nodes with their world transforms, then reads each.
#include "shadowref/scene/gltf_scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>

#include "gltf_model.hpp"
#include "json_node.hpp"
#include "receiver_check.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/identifier.hpp"

namespace shadowref::scene {
namespace {

namespace fs = std::filesystem;
using detail::JsonNode;

[[noreturn]] void refuse(const fs::path& file, const std::string& what) { throw SceneError(file.string() + ": " + what); }

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A node found by the walk, with its world transform.
struct Placed {
  int node = -1;
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
};

// The nodes that matter, in walk order (depth first, children in the file's order).
struct Walk {
  std::optional<Placed> camera;
  std::vector<std::pair<Placed, int>> lights;  // the node and its KHR_lights_punctual light index
  std::vector<Placed> meshes;
};

void walk(const tinygltf::Model& model, const std::vector<Eigen::Matrix4d>& locals, const fs::path& file, int index,
          const Eigen::Matrix4d& parent, int depth, std::size_t& instances, Walk& w) {
  const tinygltf::Node* node = nullptr;
  try {
    node = &detail::walk_node(model, index, depth, instances);
  } catch (const MeshFileError& e) {
    refuse(file, e.what());
  }
  const Placed here{index, parent * locals[static_cast<std::size_t>(index)]};
  const std::string where = "node " + std::to_string(index) + (node->name.empty() ? "" : " '" + node->name + "'");
  if (node->camera >= 0 && !w.camera) w.camera = here;
  if (const auto it = node->extensions.find("KHR_lights_punctual"); it != node->extensions.end()) {
    const tinygltf::Value& v = it->second;
    if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsInt())
      refuse(file, where + ": extensions.KHR_lights_punctual must be {\"light\": <index>}");
    const int light = v.Get("light").GetNumberAsInt();
    if (light < 0 || static_cast<std::size_t>(light) >= model.lights.size())
      refuse(file, where + ": KHR_lights_punctual light " + std::to_string(light) + " does not exist");
    w.lights.emplace_back(here, light);
  }
  if (node->mesh >= 0) {
    if (static_cast<std::size_t>(node->mesh) >= model.meshes.size())
      refuse(file, where + ": mesh " + std::to_string(node->mesh) + " does not exist");
    w.meshes.push_back(here);
  }
  for (const int child : node->children) walk(model, locals, file, child, here.world, depth + 1, instances, w);
}

// The extras object of a glTF element as JSON (open_gltf keeps its text), and its path for messages.
struct Extras {
  nlohmann::json value = nlohmann::json::object();
  std::string path;
};

Extras extras_of(const std::string& json_text, std::string path, const fs::path& file) {
  Extras e{nlohmann::json::object(), std::move(path)};
  if (json_text.empty()) return e;
  e.value = nlohmann::json::parse(json_text, nullptr, false);
  if (e.value.is_discarded()) refuse(file, e.path + ": cannot be parsed as JSON");
  return e;
}

Vec3<double> column(const Eigen::Matrix4d& m, int c) { return m.block<3, 1>(0, c); }

Vec3<double> unit_axis(const Eigen::Matrix4d& m, int c, double sign, const fs::path& file, const std::string& where) {
  const Vec3<double> v = sign * column(m, c);
  if (!(v.norm() > 0) || !v.allFinite()) refuse(file, where + ": its transform collapses its " + "xyz"[c] + " axis (a zero scale)");
  return v.normalized();
}

// The camera and the resolution (gltf_scene.hpp, "camera").
void read_camera(const tinygltf::Model& model, const fs::path& file, const Placed& at, Scene& s) {
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(at.node)];
  const std::string where = "node " + std::to_string(at.node) + (node.name.empty() ? "" : " '" + node.name + "'");
  if (static_cast<std::size_t>(node.camera) >= model.cameras.size())
    refuse(file, where + ": camera " + std::to_string(node.camera) + " does not exist");
  const tinygltf::Camera& cam = model.cameras[static_cast<std::size_t>(node.camera)];
  if (cam.type != "perspective")
    refuse(file, where + ": the first camera is '" + cam.type + "': only perspective cameras are read (the suite's camera is perspective)");
  const tinygltf::PerspectiveCamera& p = cam.perspective;
  if (!(p.yfov > 0 && p.yfov < std::numbers::pi)) refuse(file, where + ": yfov must be in (0, pi) radians");
  if (!(p.znear > 0) || !std::isfinite(p.znear)) refuse(file, where + ": znear must be > 0");
  if (p.zfar != 0 && !(p.zfar > p.znear && std::isfinite(p.zfar))) refuse(file, where + ": zfar must be > znear");
  if (p.aspectRatio != 0 && !(p.aspectRatio > 0 && std::isfinite(p.aspectRatio))) refuse(file, where + ": aspectRatio must be > 0");
  // Resolution: the node's extras.resolution, else kGltfDefaultHeight and the aspect's width.
  const Extras extras = extras_of(node.extras_json_string, "nodes[" + std::to_string(at.node) + "].extras", file);
  const JsonNode x(extras.value, extras.path, file);
  if (x.value().is_object() && x.has("resolution")) {
    const JsonNode r = x.child("resolution");
    if (r.array_size() != 2) r.fail("must be [width, height]");
    for (std::size_t i = 0; i < 2; ++i) {
      const long long v = r.element(i).integer();
      if (v < 1 || v > outputs::kMaxResolution) r.element(i).fail("must be in [1, " + std::to_string(outputs::kMaxResolution) + "]");
      (i == 0 ? s.width : s.height) = static_cast<int>(v);
    }
    // Within a pixel: the pack writes aspectRatio = W / H exactly; a width rounded from an aspect is off by < 1.
    if (p.aspectRatio != 0 && !(std::abs(static_cast<double>(s.width) - p.aspectRatio * s.height) <= 1.0))
      refuse(file, where + ": aspectRatio " + std::to_string(p.aspectRatio) + " disagrees with extras.resolution " +
                       std::to_string(s.width) + "x" + std::to_string(s.height));
  } else {
    s.height = kGltfDefaultHeight;
    const double w = std::round((p.aspectRatio != 0 ? p.aspectRatio : 1.0) * kGltfDefaultHeight);
    if (!(w >= 1 && w <= outputs::kMaxResolution))
      refuse(file, where + ": aspectRatio " + std::to_string(p.aspectRatio) + " gives a width outside [1, " +
                       std::to_string(outputs::kMaxResolution) + "] at height " + std::to_string(kGltfDefaultHeight));
    s.width = static_cast<int>(w);
  }
  Camera& c = s.camera;
  c.position = column(at.world, 3);
  if (!c.position.allFinite()) refuse(file, where + ": the camera's position is not finite");
  c.target = c.position + unit_axis(at.world, 2, -1.0, file, where);
  c.up = unit_axis(at.world, 1, 1.0, file, where);
  c.fovy_deg = p.yfov * 180.0 / std::numbers::pi;
  c.near = p.znear;
  if (p.zfar != 0) c.far = p.zfar;
  // The matrices both renderers build, in both precisions (as load_scene checks a JSON camera).
  for (const auto& err : {view_matrix<double>(c).ok() ? std::optional<Error>() : view_matrix<double>(c).error(),
                          view_matrix<float>(c).ok() ? std::optional<Error>() : view_matrix<float>(c).error()})
    if (err) refuse(file, where + ": the camera's view: " + describe(*err));
  const auto pd = projection_matrix<double>(c, s.width, s.height);
  const auto pf = projection_matrix<float>(c, s.width, s.height);
  if (!pd.ok()) refuse(file, where + ": the camera's projection: " + std::string(pd.message()));
  if (!pf.ok()) refuse(file, where + ": the camera's projection: " + std::string(pf.message()) + " (in float)");
}

// A rect light from its KHR light's extras (gltf_scene.hpp, "lights"), centred on its node.
Light read_rect(const JsonNode& x, const Vec3<double>& node_position, const fs::path& file, const std::string& where) {
  x.expect_object({"shadowref_type", "corner", "edge_u", "edge_v", "samples", "index", "mask_file", "size", "note"});
  Light l;
  l.type = LightType::Rect;
  l.corner = x.required("corner").vec3();
  l.edge_u = x.required("edge_u").vec3();
  l.edge_v = x.required("edge_v").vec3();
  if (!(l.edge_u.cross(l.edge_v).norm() > 0)) x.fail_at("edge_v", "must not be zero or parallel to edge_u");
  l.samples = static_cast<int>(x.integer_in("samples", 1, 64, 4));
  // The parallelogram is in scene coordinates; a node elsewhere means they were written in the
  // node's frame. 1e-6 of the light's extent and distance from the origin: the pack writes both
  // with 17 digits, and a frame mix-up moves the centre by a whole edge or position.
  const Vec3<double> centre = l.corner + 0.5 * (l.edge_u + l.edge_v);
  const double scale = std::max({1.0, centre.norm(), l.edge_u.norm(), l.edge_v.norm()});
  if (!((centre - node_position).norm() <= 1e-6 * scale))
    refuse(file, where + ": a rect light's corner, edge_u and edge_v are in scene coordinates and its node must sit at its "
                         "centre (corner + (edge_u + edge_v) / 2), but the node is " +
                         std::to_string((centre - node_position).norm()) + " away from it");
  return l;
}

Light read_light(const tinygltf::Model& model, const fs::path& file, const Placed& at, int index) {
  const tinygltf::Light& src = model.lights[static_cast<std::size_t>(index)];
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(at.node)];
  const std::string where = "node " + std::to_string(at.node) + (node.name.empty() ? "" : " '" + node.name + "'") +
                            " (KHR_lights_punctual light " + std::to_string(index) + ")";
  Light l;
  l.position = column(at.world, 3);
  if (!l.position.allFinite()) refuse(file, where + ": its position is not finite");
  const Extras extras = extras_of(src.extras_json_string, "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "].extras", file);
  const JsonNode x(extras.value, extras.path, file);
  const bool rect = x.value().is_object() && x.has("shadowref_type") && x.child("shadowref_type").string() == "rect";
  if (src.type == "directional") {
    l.type = LightType::Directional;
    l.direction = unit_axis(at.world, 2, 1.0, file, where);  // toward the light: it shines along −z
  } else if (src.type == "point" && rect) {
    return read_rect(x, l.position, file, where);
  } else if (src.type == "point") {
    l.type = LightType::Point;
  } else if (src.type == "spot") {
    l.type = LightType::Spot;
    l.direction = unit_axis(at.world, 2, -1.0, file, where);
    l.cone_deg = src.spot.outerConeAngle * 180.0 / std::numbers::pi;
    if (!(l.cone_deg > 0 && l.cone_deg <= 90)) refuse(file, where + ": outerConeAngle must be in (0, pi/2]");
  } else {
    refuse(file, where + ": unknown light type '" + src.type + "' (expected directional, point or spot)");
  }
  if (rect && src.type != "point") x.fail_at("shadowref_type", "a rect light is written as a point light (its centre)");
  return l;
}

// An object name from `base` under the identifier rule, unique among `taken`.
std::string object_name(std::string base, std::set<std::string>& taken) {
  for (char& c : base)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  while (base.find("..") != std::string::npos) base.replace(base.find(".."), 2, "_");
  if (base.empty() || !std::isalnum(static_cast<unsigned char>(base.front()))) base = "n" + base;
  base = base.substr(0, kMaxIdentifierLength - 8);  // room for a "_<k>" suffix
  std::string name = base;
  for (int k = 1; taken.count(name); ++k) name = base + "_" + std::to_string(k);
  taken.insert(name);
  return name;
}

// Reads the whole file: the not-read lines go to `notes`.
class Reader {
 public:
  Reader(const tinygltf::Model& model, const std::vector<Eigen::Matrix4d>& globals, const fs::path& file, std::set<std::string>& notes)
      : m_(model), globals_(globals), file_(file), notes_(notes) {}

  // One object per TRIANGLES primitive of the mesh node at `at`.
  void add_mesh_node(const Placed& at, std::set<std::string>& taken, Scene& s) {
    const tinygltf::Node& node = m_.nodes[static_cast<std::size_t>(at.node)];
    const tinygltf::Mesh& mesh = m_.meshes[static_cast<std::size_t>(node.mesh)];
    const std::string where = "node " + std::to_string(at.node) + (node.name.empty() ? "" : " '" + node.name + "'");
    const std::string base = !node.name.empty() ? node.name : !mesh.name.empty() ? mesh.name : "node" + std::to_string(at.node);
    const bool nonzero_weight = std::any_of(mesh.weights.begin(), mesh.weights.end(), [](double v) { return v != 0; }) ||
                                std::any_of(node.weights.begin(), node.weights.end(), [](double v) { return v != 0; });
    const Extras extras = extras_of(node.extras_json_string, "nodes[" + std::to_string(at.node) + "].extras", file_);
    const JsonNode x(extras.value, extras.path, file_);
    const bool receiver = x.value().is_object() && x.has("receiver") && x.child("receiver").boolean();
    if (receiver && mesh.primitives.size() != 1) x.fail_at("receiver", "the receiver must be a mesh of one primitive");
    for (std::size_t k = 0; k < mesh.primitives.size(); ++k) {
      const tinygltf::Primitive& prim = mesh.primitives[k];
      if (!prim.targets.empty()) {
        if (nonzero_weight)
          refuse(file_, where + ": morph targets with a non-zero weight are not read (the shape would be silently wrong)");
        notes_.insert("morph targets are not read (all their weights are 0: the base meshes are the shape)");
      }
      Object o;
      o.name = object_name(k == 0 ? base : base + "_" + std::to_string(k), taken);
      o.shape = "mesh";
      o.receiver = receiver;
      std::vector<Vec3<double>> positions;
      std::vector<std::uint32_t> indices;
      try {
        if (node.skin >= 0) {  // posed by its skin; the node's own transform is not applied (glTF 2.0 §3.7.3)
          detail::SkinBuilder builder(m_, globals_);
          positions = builder.add_skinned(prim, node.skin);
          o.skin = builder.take();
        } else {
          positions = detail::primitive_positions(m_, prim, at.world);
        }
        indices = detail::primitive_indices(m_, prim, positions.size());
      } catch (const MeshFileError& e) {
        refuse(file_, where + ", primitive " + std::to_string(k) + ": " + e.what());
      }
      if (indices.empty()) continue;  // a primitive without triangles adds nothing
      for (const auto& p : positions) {
        const Vec3<float> f = p.cast<float>();
        if (!f.allFinite()) refuse(file_, where + ": its transform moves a vertex to a non-finite position (overflow in float)");
        o.mesh.positions.push_back(f);
      }
      const bool mirror = !o.skin && at.world.topLeftCorner<3, 3>().determinant() < 0;
      for (std::size_t i = 0; i < indices.size(); i += 3)
        o.mesh.triangles.push_back(mirror ? std::array<std::uint32_t, 3>{indices[i], indices[i + 2], indices[i + 1]}
                                          : std::array<std::uint32_t, 3>{indices[i], indices[i + 1], indices[i + 2]});
      read_material(prim, where + ", primitive " + std::to_string(k), o);
      if (receiver && s.receiver_index())
        x.fail_at("receiver", "only one object may be the receiver ('" + s.objects[*s.receiver_index()].name + "' already is)");
      s.objects.push_back(std::move(o));
      if (receiver && !detail::receiver_is_planar(s)) x.fail_at("receiver", "the receiver must be planar (all its vertices on one plane)");
    }
  }

  // Textures no mask reads, counted over every material (said once).
  void note_other_textures() {
    std::size_t other = 0;
    for (std::size_t i = 0; i < m_.materials.size(); ++i) {
      const tinygltf::Material& mat = m_.materials[i];
      other += (mat.normalTexture.index >= 0) + (mat.occlusionTexture.index >= 0) + (mat.emissiveTexture.index >= 0) +
               (mat.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0) +
               (mat.alphaMode != "MASK" && mat.pbrMetallicRoughness.baseColorTexture.index >= 0);
    }
    if (other)
      notes_.insert(std::to_string(other) + " texture reference(s) other than MASK materials' baseColorTexture ignored "
                    "(normal, occlusion, emissive, metallic-roughness, an OPAQUE or BLEND base colour): only the alpha mask "
                    "changes a shadow");
  }

 private:
  // The primitive's material: its colour and, for alphaMode MASK, its alpha mask.
  void read_material(const tinygltf::Primitive& prim, const std::string& where, Object& o) {
    if (prim.material < 0) return;
    if (static_cast<std::size_t>(prim.material) >= m_.materials.size())
      refuse(file_, where + ": material " + std::to_string(prim.material) + " does not exist");
    const tinygltf::Material& mat = m_.materials[static_cast<std::size_t>(prim.material)];
    const std::string what = where + ": material " + std::to_string(prim.material) + (mat.name.empty() ? "" : " '" + mat.name + "'");
    const std::vector<double>& factor = mat.pbrMetallicRoughness.baseColorFactor;
    if (factor.size() == 4) {
      for (double c : factor)
        if (!(c >= 0 && c <= 1)) refuse(file_, what + ": baseColorFactor must be within [0, 1]");
      o.color = Vec3<float>(static_cast<float>(factor[0]), static_cast<float>(factor[1]), static_cast<float>(factor[2]));
    }
    if (mat.alphaMode == "BLEND") {
      notes_.insert("alphaMode BLEND is read as OPAQUE: a blended surface casts a solid shadow here (engines differ)");
      return;
    }
    if (mat.alphaMode != "MASK") return;
    if (!(mat.alphaCutoff >= 0 && mat.alphaCutoff <= 1)) refuse(file_, what + ": alphaCutoff must be in [0, 1]");
    const float factor_alpha = factor.size() == 4 ? static_cast<float>(factor[3]) : 1.0f;
    const std::size_t n = o.mesh.positions.size();
    AlphaMask mask;
    mask.cutoff = mat.alphaCutoff;
    mask.texture = std::make_shared<const AlphaTexture>();
    mask.uvs.assign(n, Vec2<float>::Zero());
    mask.vertex_alpha.assign(n, factor_alpha);
    mask.has_vertex_alpha = factor_alpha != 1.0f;
    if (const auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
      int components = 0;
      const std::vector<float> c = attribute(it->second, 4, 3, what + ": COLOR_0", n, components);
      if (components == 4) {
        mask.has_vertex_alpha = true;
        for (std::size_t i = 0; i < n; ++i) {
          const float a = c[4 * i + 3];
          if (!(a >= 0 && a <= 1)) refuse(file_, what + ": COLOR_0 alpha of vertex " + std::to_string(i) + " is outside [0, 1]");
          mask.vertex_alpha[i] = a * factor_alpha;
        }
      }
    }
    const tinygltf::TextureInfo& info = mat.pbrMetallicRoughness.baseColorTexture;
    bool textured = false;
    if (info.index >= 0) textured = read_mask_texture(prim, info, what, mask);
    // Alpha 1 everywhere (no texture alpha, no vertex alpha) is opaque at any cutoff in [0, 1].
    if (textured || mask.has_vertex_alpha) o.alpha = std::move(mask);
  }

  // The mask's texture, its coordinates and sampler; false when it has no alpha channel (alpha 1).
  bool read_mask_texture(const tinygltf::Primitive& prim, const tinygltf::TextureInfo& info, const std::string& what, AlphaMask& mask) {
    if (info.extensions.count("KHR_texture_transform"))
      refuse(file_, what + ": the mask's baseColorTexture has KHR_texture_transform, which is not read (the mask would be misplaced)");
    if (static_cast<std::size_t>(info.index) >= m_.textures.size())
      refuse(file_, what + ": texture " + std::to_string(info.index) + " does not exist");
    const tinygltf::Texture& tex = m_.textures[static_cast<std::size_t>(info.index)];
    if (tex.source < 0 || static_cast<std::size_t>(tex.source) >= m_.images.size())
      refuse(file_, what + ": the mask's texture " + std::to_string(info.index) + " has no image shadowref can read (a PNG)");
    const tinygltf::Image& image = m_.images[static_cast<std::size_t>(tex.source)];
    const std::string image_name = "image " + std::to_string(tex.source) + (image.uri.empty() || image.uri.rfind("data:", 0) == 0 ? "" : " '" + image.uri + "'");
    // The type the image declares, or its data: URI's (a file's bytes must be a PNG's in any case).
    std::string mime = image.mimeType;
    if (mime.empty() && image.uri.rfind("data:", 0) == 0) mime = image.uri.substr(5, image.uri.find_first_of(";,") - 5);
    if (!mime.empty() && mime != "image/png" && mime != "application/octet-stream")
      refuse(file_, what + ": the mask is " + image_name + " of type " + mime + ": only PNG masks are read");
    std::string bytes;
    try {
      bytes = detail::image_bytes(m_, tex.source);
    } catch (const MeshFileError& e) {
      refuse(file_, what + ": " + e.what());
    }
    if (bytes.empty())
      refuse(file_, what + ": the mask, " + image_name + ", cannot be read (a missing file, or one outside the glTF file's folder)");
    outputs::Image8 png;
    try {
      png = outputs::decode_png8(bytes, file_.string() + ": " + what + ": the mask, " + image_name);
    } catch (const outputs::InputError& e) {
      throw SceneError(e.what());
    }
    std::shared_ptr<const AlphaTexture> texture;
    try {
      // embedded: the glTF file stands for it (non-empty: a texture, not vertex alpha only)
      texture = alpha_texture_of(png, file_, WithoutAlpha::Opaque);
    } catch (const std::invalid_argument& e) {
      refuse(file_, what + ": the mask, " + image_name + ", is " + e.what());
    }
    if (!texture) {
      notes_.insert("a MASK material's baseColorTexture without an alpha channel has alpha 1 (glTF): only its vertex alpha and "
                    "baseColorFactor's alpha mask it");
      return false;
    }
    const std::size_t n = mask.uvs.size();
    int components = 0;
    const std::string coord = "TEXCOORD_" + std::to_string(info.texCoord);
    const auto it = prim.attributes.find(coord);
    if (it == prim.attributes.end()) refuse(file_, what + ": the mask's texture reads " + coord + ", which the primitive lacks");
    const std::vector<float> uv = attribute(it->second, 2, 0, what + ": " + coord, n, components);
    bool in_unit_square = true;
    for (std::size_t i = 0; i < n; ++i) {
      mask.uvs[i] = Vec2<float>(uv[2 * i], uv[2 * i + 1]);
      if (!(static_cast<double>(mask.uvs[i].cwiseAbs().maxCoeff()) <= kMaxAlphaUv))
        refuse(file_, what + ": " + coord + " of vertex " + std::to_string(i) + " is outside [-64, 64] (alpha_mask.hpp, kMaxAlphaUv)");
      in_unit_square = in_unit_square && mask.uvs[i].minCoeff() >= 0 && mask.uvs[i].maxCoeff() <= 1;
    }
    if (tex.sampler >= 0) {
      if (static_cast<std::size_t>(tex.sampler) >= m_.samplers.size()) refuse(file_, what + ": sampler " + std::to_string(tex.sampler) + " does not exist");
      const tinygltf::Sampler& sampler = m_.samplers[static_cast<std::size_t>(tex.sampler)];
      const bool nearest = (sampler.magFilter == -1 || sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) &&
                           (sampler.minFilter == -1 || sampler.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST);
      if (!nearest)
        notes_.insert("a mask's sampler filters other than NEAREST: the suite's rule reads the nearest texel (docs/scene-format.md), "
                      "so a mask edge may differ from a filtering engine's by up to a texel");
      const bool repeat = sampler.wrapS == TINYGLTF_TEXTURE_WRAP_REPEAT && sampler.wrapT == TINYGLTF_TEXTURE_WRAP_REPEAT;
      if (!repeat && !in_unit_square)
        refuse(file_, what + ": the mask's sampler clamps or mirrors and its " + coord + " leaves [0, 1]: the suite's rule wraps "
                             "(REPEAT), so the mask would differ");
    }
    mask.texture = std::move(texture);
    return true;
  }

  std::vector<float> attribute(int accessor, int components, int or_components, const std::string& what, std::size_t vertices,
                               int& got) {
    std::vector<float> values;
    try {
      values = detail::read_float_attribute(m_, accessor, components, or_components, what, got);
    } catch (const MeshFileError& e) {
      refuse(file_, e.what());
    }
    if (values.size() != vertices * static_cast<std::size_t>(got))
      refuse(file_, what + " has " + std::to_string(values.size() / static_cast<std::size_t>(got)) + " elements, POSITION has " +
                        std::to_string(vertices));
    return values;
  }

  const tinygltf::Model& m_;
  const std::vector<Eigen::Matrix4d>& globals_;
  const fs::path& file_;
  std::set<std::string>& notes_;
};

// Extensions: those that change nothing a mask sees are fine; any other required one is refused,
// any other used one said.
void check_extensions(const tinygltf::Model& model, const fs::path& file, std::set<std::string>& notes) {
  const auto shading_only = [](const std::string& e) { return e == "KHR_lights_punctual" || e.rfind("KHR_materials_", 0) == 0; };
  for (const std::string& e : model.extensionsRequired)
    if (!shading_only(e)) refuse(file, "extensionsRequired names " + e + ", which shadowref does not read");
  for (const std::string& e : model.extensionsUsed)
    if (!shading_only(e) && e != "KHR_texture_transform") notes.insert("extension " + e + " is not read");
}

}  // namespace

bool is_gltf_scene_file(const fs::path& file) {
  const std::string ext = lower(file.extension().string());
  return ext == ".gltf" || ext == ".glb";
}

bool holds_camera_and_light(const fs::path& file) {
  if (!is_gltf_scene_file(file)) return false;
  std::ifstream in(file, std::ios::binary);
  std::string text;
  if (lower(file.extension().string()) == ".glb") {
    // GLB: a 12-byte header, then the JSON chunk's length and type ("JSON"), then the JSON.
    char head[20];
    if (!in.read(head, sizeof head)) return false;
    std::uint32_t words[5];
    std::memcpy(words, head, sizeof words);
    if (words[0] != 0x46546C67u || words[4] != 0x4E4F534Au || words[3] > (std::uint32_t{64} << 20)) return false;
    text.resize(words[3]);
    if (!in.read(text.data(), static_cast<std::streamsize>(text.size()))) return false;
  } else {
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) return false;
  const auto cameras = j.find("cameras");
  const nlohmann::json* lights = nullptr;
  if (const auto e = j.find("extensions"); e != j.end() && e->is_object())
    if (const auto k = e->find("KHR_lights_punctual"); k != e->end() && k->is_object())
      if (const auto l = k->find("lights"); l != k->end()) lights = &*l;
  return cameras != j.end() && cameras->is_array() && !cameras->empty() && lights && lights->is_array() && !lights->empty();
}

GltfScene read_gltf_scene(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) refuse(file, "cannot open the scene file");
  GltfScene out;
  Scene& s = out.scene;
  s.file = file;
  s.name = file.stem().string();
  if (auto problem = identifier_problem(s.name))
    refuse(file, "the scene's name is the file's stem '" + s.name + "', which " + *problem + ": rename the file");
  s.description = "glTF scene " + file.filename().string();
  tinygltf::Model model;
  try {
    model = detail::open_gltf(file, lower(file.extension().string()) == ".glb", true);
  } catch (const MeshFileError& e) {
    refuse(file, e.what());
  }
  std::set<std::string> notes;
  check_extensions(model, file, notes);
  // glTF's unit is the metre; a scene written by `shadowref export` in another one says so in its
  // scene's extras.units (scene.hpp, LengthUnit).
  if (const std::optional<std::size_t> at = detail::shown_scene(model)) {
    const Extras extras = extras_of(model.scenes[*at].extras_json_string, "scenes[" + std::to_string(*at) + "].extras", file);
    if (const auto u = extras.value.find("units"); u != extras.value.end()) {
      const LengthUnit* unit = u->is_string() ? find_length_unit(u->get<std::string>()) : nullptr;
      if (!unit) refuse(file, extras.path + ".units: must be one of " + length_unit_symbols() + " (glTF's own unit is the metre)");
      s.units = *unit;
    }
  }
  // The pose (docs/scene-format.md, "Skins"): the first animation at its extras.pose_time, else 0.
  std::vector<Eigen::Matrix4d> locals, globals;
  try {
    locals = detail::posed_local_transforms(model, detail::pose_time(model));
    if (!model.skins.empty()) globals = detail::global_transforms(model, locals);
  } catch (const MeshFileError& e) {
    refuse(file, e.what());
  }
  if (model.animations.size() > 1)
    notes.insert(std::to_string(model.animations.size() - 1) + " animation(s) after the first are not read (the pose is the first's)");
  Walk w;
  std::size_t instances = 0;
  for (const int root : detail::scene_roots(model)) walk(model, locals, file, root, Eigen::Matrix4d::Identity(), 0, instances, w);
  if (!w.camera) refuse(file, "no camera: shadowref judges the view of the scene's first camera node (add a perspective camera)");
  read_camera(model, file, *w.camera, s);
  if (w.lights.empty()) refuse(file, "no light: shadowref reads KHR_lights_punctual lights (directional, point, spot)");
  for (const auto& [at, light] : w.lights) s.lights.push_back(read_light(model, file, at, light));
  Reader reader(model, globals, file, notes);
  std::set<std::string> taken;
  for (const Placed& at : w.meshes) reader.add_mesh_node(at, taken, s);
  if (s.objects.empty()) refuse(file, "no triangles: shadowref reads the TRIANGLES primitives of the scene's mesh nodes");
  reader.note_other_textures();
  out.not_read.assign(notes.begin(), notes.end());
  return out;
}

}  // namespace shadowref::scene
