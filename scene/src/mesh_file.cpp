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

void append_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Eigen::Matrix4d& xf,
                      TriangleMesh<double>& mesh) {
  const std::vector<Vec3<double>> positions = detail::primitive_positions(model, prim, xf);
  const std::vector<std::uint32_t> idx = detail::primitive_indices(model, prim, positions.size());
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), positions.begin(), positions.end());
  // A mirroring node transform flips the winding; flip it back so counter-clockwise stays outside.
  const bool mirror = xf.topLeftCorner<3, 3>().determinant() < 0;
  for (std::size_t i = 0; i < idx.size(); i += 3) {
    if (mirror) mesh.triangles.push_back({base + idx[i], base + idx[i + 2], base + idx[i + 1]});
    else mesh.triangles.push_back({base + idx[i], base + idx[i + 1], base + idx[i + 2]});
  }
}

void append_node(const tinygltf::Model& model, int node_index, const Eigen::Matrix4d& parent, TriangleMesh<double>& mesh, int depth,
                 std::size_t& instances) {
  const auto& node = detail::walk_node(model, node_index, depth, instances);
  const Eigen::Matrix4d xf = parent * detail::node_transform(node);
  if (node.mesh >= 0) {
    if (static_cast<std::size_t>(node.mesh) >= model.meshes.size()) throw MeshFileError("mesh " + std::to_string(node.mesh) + " does not exist");
    for (const auto& prim : model.meshes[static_cast<std::size_t>(node.mesh)].primitives) append_primitive(model, prim, xf, mesh);
  }
  for (int child : node.children) append_node(model, child, xf, mesh, depth + 1, instances);
}

// Every TRIANGLES primitive of the file's scene (gltf_model.hpp opens it, confined to its folder).
TriangleMesh<double> load_gltf(const std::filesystem::path& path, bool binary) {
  const tinygltf::Model model = detail::open_gltf(path, binary);
  TriangleMesh<double> mesh;
  std::size_t instances = 0;
  for (int r : detail::scene_roots(model)) append_node(model, r, Eigen::Matrix4d::Identity(), mesh, 0, instances);
  return mesh;
}

}  // namespace

TriangleMesh<double> load_mesh_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw MeshFileError("no such file");
  const std::string ext = lower_extension(path);
  TriangleMesh<double> mesh;
  if (ext == ".obj") mesh = load_obj(path);
  else if (ext == ".gltf") mesh = load_gltf(path, false);
  else if (ext == ".glb") mesh = load_gltf(path, true);
  else throw MeshFileError("unknown mesh format '" + ext + "' (expected .obj, .gltf or .glb)");
  if (mesh.triangles.empty()) throw MeshFileError("the mesh has no triangles");
  return mesh;
}

}  // namespace shadowref::scene
