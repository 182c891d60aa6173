// mesh_file.cpp — OBJ and glTF loading for mesh_file.hpp. OBJ faces are validated and triangulated
// here rather than by tinyobjloader, whose triangulation reads vertex positions through unchecked
// indices (an out-of-range index would be an out-of-bounds read before we could refuse it), and
// OBJ coordinates are checked before tinyobjloader reads them (it turns "nan" into 0).
#include "shadowref/scene/mesh_file.hpp"

#include <tiny_obj_loader.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "gltf_model.hpp"

namespace shadowref::scene {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf", "0x1p3", "abc") or a missing
// one as 0, which would silently move a vertex. So every "v" line is checked first: x, y and z
// must be plain decimal numbers (digits, sign, point, exponent) that are finite in double.
// Streams the file line by line (no copy of a large file in memory).
bool is_decimal_token(const std::string& t) {
  if (t.empty()) return false;
  bool digit = false;
  for (const char c : t) {
    if (c >= '0' && c <= '9') digit = true;
    else if (c != '+' && c != '-' && c != '.' && c != 'e' && c != 'E') return false;
  }
  return digit;
}

void check_obj_coordinates(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshFileError("cannot open the file");
  std::string line;
  std::size_t vertex = 0;
  while (std::getline(in, line)) {
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos || line.compare(i, 1, "v") != 0 || i + 1 >= line.size() ||
        (line[i + 1] != ' ' && line[i + 1] != '\t'))
      continue;
    ++vertex;
    i += 1;
    for (int k = 0; k < 3; ++k) {
      const std::size_t b = line.find_first_not_of(" \t\r", i);
      const std::size_t e = b == std::string::npos ? std::string::npos : line.find_first_of(" \t\r", b);
      const std::string token = b == std::string::npos ? std::string() : line.substr(b, e == std::string::npos ? std::string::npos : e - b);
      if (token.empty()) throw MeshFileError("vertex " + std::to_string(vertex) + " has fewer than 3 coordinates");
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      const bool parsed = end == token.c_str() + token.size();
      if (parsed && !std::isfinite(v)) throw MeshFileError("vertex " + std::to_string(vertex) + " is NaN or infinite");
      if (!parsed || !is_decimal_token(token)) {
        // strtod also reads "nan", "inf", "infinity" and hex floats: name NaN and infinity as such.
        std::string lower = token;
        std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
          throw MeshFileError("vertex " + std::to_string(vertex) + " is NaN or infinite");
        throw MeshFileError("vertex " + std::to_string(vertex) + " has a coordinate '" + token.substr(0, 40) +
                            "' that is not a decimal number");
      }
      i = e == std::string::npos ? line.size() : e;
    }
  }
  if (in.bad()) throw MeshFileError("cannot read the file");
}

TriangleMesh<double> load_obj(const std::filesystem::path& path) {
  check_obj_coordinates(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // see the file comment
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string(), config)) {
    throw MeshFileError("cannot parse OBJ: " + detail::first_line(reader.Error()));
  }
  const auto& coords = reader.GetAttrib().vertices;
  const std::size_t vertex_count = coords.size() / 3;
  TriangleMesh<double> mesh;
  mesh.positions.reserve(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const Vec3<double> p(static_cast<double>(coords[3 * i]), static_cast<double>(coords[3 * i + 1]),
                         static_cast<double>(coords[3 * i + 2]));
    if (!p.allFinite()) throw MeshFileError("vertex " + std::to_string(i + 1) + " is NaN or infinite");
    mesh.positions.push_back(p);
  }
  for (const auto& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t n = shape.mesh.num_face_vertices[f];
      std::vector<std::uint32_t> ids;
      for (std::size_t k = 0; k < n; ++k) {
        const int idx = shape.mesh.indices[offset + k].vertex_index;
        if (idx < 0 || static_cast<std::size_t>(idx) >= vertex_count) {
          throw MeshFileError("face " + std::to_string(f + 1) + " of shape '" + shape.name +
                              "' uses vertex " + std::to_string(idx + 1) + " but the file has " +
                              std::to_string(vertex_count) + " vertices");
        }
        ids.push_back(static_cast<std::uint32_t>(idx));
      }
      offset += n;
      for (std::size_t k = 1; k + 1 < ids.size(); ++k) mesh.triangles.push_back({ids[0], ids[k], ids[k + 1]});
    }
  }
  return mesh;
}

// Appends one primitive's triangles over `positions` (its vertices, already in world space).
void append_triangles(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::vector<Vec3<double>>& positions,
                      bool mirror, TriangleMesh<double>& mesh) {
  const std::vector<std::uint32_t> idx = detail::primitive_indices(model, prim, positions.size());
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), positions.begin(), positions.end());
  // A mirroring node transform flips the winding; flip it back so counter-clockwise stays outside.
  for (std::size_t i = 0; i < idx.size(); i += 3) {
    if (mirror) mesh.triangles.push_back({base + idx[i], base + idx[i + 2], base + idx[i + 1]});
    else mesh.triangles.push_back({base + idx[i], base + idx[i + 1], base + idx[i + 2]});
  }
}

struct GltfWalk {
  const tinygltf::Model& model;
  const std::vector<Eigen::Matrix4d>& locals;
  detail::SkinBuilder* skin;  // null: the file has no skin
  PosedMesh& out;
  std::size_t instances = 0;

  void node(int node_index, const Eigen::Matrix4d& parent, int depth) {
    const auto& node = detail::walk_node(model, node_index, depth, instances);
    const Eigen::Matrix4d xf = parent * locals[static_cast<std::size_t>(node_index)];
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= model.meshes.size()) throw MeshFileError("mesh " + std::to_string(node.mesh) + " does not exist");
      for (const auto& prim : model.meshes[static_cast<std::size_t>(node.mesh)].primitives) {
        if (!skin) append_triangles(model, prim, detail::primitive_positions(model, prim, xf), xf.topLeftCorner<3, 3>().determinant() < 0, out.mesh);
        else if (node.skin >= 0) append_triangles(model, prim, skin->add_skinned(prim, node.skin), false, out.mesh);  // the node's transform is not applied (glTF)
        else append_triangles(model, prim, skin->add_rigid(prim, xf), xf.topLeftCorner<3, 3>().determinant() < 0, out.mesh);
      }
    }
    for (int child : node.children) this->node(child, xf, depth + 1);
  }
};

// Every TRIANGLES primitive of the file's scene at its pose (gltf_model.hpp opens it, confined to its folder).
PosedMesh load_gltf(const std::filesystem::path& path, bool binary, std::optional<double> pose_time) {
  const tinygltf::Model model = detail::open_gltf(path, binary);
  const double time = pose_time ? *pose_time : detail::pose_time(model);
  const std::vector<Eigen::Matrix4d> locals = detail::posed_local_transforms(model, time);
  const bool skinned = std::any_of(model.nodes.begin(), model.nodes.end(), [](const tinygltf::Node& n) { return n.skin >= 0 && n.mesh >= 0; });
  std::optional<std::vector<Eigen::Matrix4d>> globals;
  std::optional<detail::SkinBuilder> builder;
  if (skinned) {
    globals = detail::global_transforms(model, locals);
    builder.emplace(model, *globals);
  }
  PosedMesh out;
  GltfWalk walk{model, locals, builder ? &*builder : nullptr, out};
  for (int r : detail::scene_roots(model)) walk.node(r, Eigen::Matrix4d::Identity(), 0);
  if (builder) out.skin = builder->take();
  return out;
}

}  // namespace

TriangleMesh<double> load_mesh_file(const std::filesystem::path& path) { return load_posed_mesh_file(path).mesh; }

PosedMesh load_posed_mesh_file(const std::filesystem::path& path, std::optional<double> pose_time) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw MeshFileError("no such file");
  const std::string ext = lower_extension(path);
  PosedMesh out;
  if (ext == ".obj") out.mesh = load_obj(path);
  else if (ext == ".gltf") out = load_gltf(path, false, pose_time);
  else if (ext == ".glb") out = load_gltf(path, true, pose_time);
  else throw MeshFileError("unknown mesh format '" + ext + "' (expected .obj, .gltf or .glb)");
  if (out.mesh.triangles.empty()) throw MeshFileError("the mesh has no triangles");
  return out;
}

}  // namespace shadowref::scene
