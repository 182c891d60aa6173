// mesh_file.cpp — OBJ and glTF loading for mesh_file.hpp. OBJ faces are validated and triangulated
// here rather than by tinyobjloader, whose triangulation reads vertex positions through unchecked
// indices (an out-of-range index would be an out-of-bounds read before we could refuse it), and
// OBJ coordinates are checked before tinyobjloader reads them (it turns "nan" into 0).
#include "shadowref/scene/mesh_file.hpp"

#include <tiny_gltf.h>
#include <tiny_obj_loader.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "shadowref/scene/path_within.hpp"

namespace shadowref::scene {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string first_line(const std::string& text) {
  std::string s = text.substr(0, text.find('\n'));
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
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
    throw MeshFileError("cannot parse OBJ: " + first_line(reader.Error()));
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

// The node's local transform: its matrix, or T * R * S from its translation, rotation, scale.
Eigen::Matrix4d node_transform(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<std::size_t>(4 * c + r)];  // column-major
    return m;
  }
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  if (node.translation.size() == 3) a.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4) {
    a.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
  }
  if (node.scale.size() == 3) a.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  return a.matrix();
}

// The bytes of accessor `index` as (pointer to element 0, stride), with bounds checked.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
};

AccessorView view_accessor(const tinygltf::Model& model, int index, std::size_t element_size) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) throw MeshFileError("accessor " + std::to_string(index) + " does not exist");
  const auto& acc = model.accessors[static_cast<std::size_t>(index)];
  if (acc.bufferView < 0 || static_cast<std::size_t>(acc.bufferView) >= model.bufferViews.size()) {
    throw MeshFileError("accessor " + std::to_string(index) + " has no buffer view (sparse accessors are not supported)");
  }
  const auto& bv = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size()) throw MeshFileError("buffer view without a buffer");
  const auto& buf = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
  AccessorView v;
  v.stride = bv.byteStride ? bv.byteStride : element_size;
  v.count = acc.count;
  const std::size_t begin = bv.byteOffset + acc.byteOffset;
  const std::size_t end = acc.count == 0 ? begin : begin + (acc.count - 1) * v.stride + element_size;
  if (end > buf.size() || bv.byteOffset + bv.byteLength > buf.size() || end > bv.byteOffset + bv.byteLength) {
    throw MeshFileError("accessor " + std::to_string(index) + " reads past the end of its buffer");
  }
  v.data = buf.data() + begin;
  return v;
}

void append_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Eigen::Matrix4d& xf,
                      TriangleMesh<double>& mesh) {
  if (prim.mode != TINYGLTF_MODE_TRIANGLES) throw MeshFileError("a primitive has mode " + std::to_string(prim.mode) + ", only TRIANGLES (4) is supported");
  const auto pos_it = prim.attributes.find("POSITION");
  if (pos_it == prim.attributes.end()) throw MeshFileError("a primitive has no POSITION attribute");
  // Indices into the model are the file's word: check them (found by reliability/fuzz/gltf_fuzzer:
  // vector::at's std::out_of_range used to escape as an uncaught exception).
  const auto accessor = [&](int index) -> const tinygltf::Accessor& {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
      throw MeshFileError("accessor " + std::to_string(index) + " does not exist");
    return model.accessors[static_cast<std::size_t>(index)];
  };
  const auto& pos_acc = accessor(pos_it->second);
  if (pos_acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pos_acc.type != TINYGLTF_TYPE_VEC3) {
    throw MeshFileError("POSITION must be a float VEC3 accessor");
  }
  const AccessorView pos = view_accessor(model, pos_it->second, 3 * sizeof(float));
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::size_t i = 0; i < pos.count; ++i) {
    float p[3];
    std::memcpy(p, pos.data + i * pos.stride, sizeof p);
    const Eigen::Vector4d w = xf * Eigen::Vector4d(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]), 1.0);
    const Vec3<double> q = w.head<3>() / w[3];
    if (!q.allFinite()) throw MeshFileError("vertex " + std::to_string(i) + " is NaN or infinite");
    mesh.positions.push_back(q);
  }
  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    const auto& acc = accessor(prim.indices);
    std::size_t size = 0;
    switch (acc.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
      default: throw MeshFileError("indices must be unsigned byte, short or int");
    }
    const AccessorView v = view_accessor(model, prim.indices, size);
    for (std::size_t i = 0; i < v.count; ++i) {
      const unsigned char* e = v.data + i * v.stride;
      std::uint32_t x = 0;
      if (size == 1) x = *e;
      else if (size == 2) { std::uint16_t s; std::memcpy(&s, e, 2); x = s; }
      else std::memcpy(&x, e, 4);
      idx.push_back(x);
    }
  } else {
    for (std::size_t i = 0; i < pos.count; ++i) idx.push_back(static_cast<std::uint32_t>(i));
  }
  if (idx.size() % 3 != 0) throw MeshFileError("a TRIANGLES primitive has " + std::to_string(idx.size()) + " indices, not a multiple of 3");
  for (std::size_t i = 0; i < idx.size(); i += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (idx[i + k] >= pos.count) {
        throw MeshFileError("index " + std::to_string(idx[i + k]) + " is out of range (" + std::to_string(pos.count) + " vertices)");
      }
    }
    // A mirroring node transform flips the winding; flip it back so counter-clockwise stays outside.
    const bool mirror = xf.topLeftCorner<3, 3>().determinant() < 0;
    if (mirror) mesh.triangles.push_back({base + idx[i], base + idx[i + 2], base + idx[i + 1]});
    else mesh.triangles.push_back({base + idx[i], base + idx[i + 1], base + idx[i + 2]});
  }
}

// A hierarchy that names the same node many times over (node i's children [i+1, i+1], 60 deep) is
// small on disk and 2^60 instances when walked: the walk stops at this many node instances.
constexpr std::size_t kMaxNodeInstances = std::size_t{1} << 20;

void append_node(const tinygltf::Model& model, int node_index, const Eigen::Matrix4d& parent, TriangleMesh<double>& mesh, int depth,
                 std::size_t& instances) {
  if (node_index < 0 || static_cast<std::size_t>(node_index) >= model.nodes.size()) throw MeshFileError("node " + std::to_string(node_index) + " does not exist");
  if (depth > 64) throw MeshFileError("the node hierarchy is deeper than 64 (a cycle?)");
  if (++instances > kMaxNodeInstances)
    throw MeshFileError("the node hierarchy instances more than " + std::to_string(kMaxNodeInstances) +
                        " nodes (nodes referenced many times over)");
  const auto& node = model.nodes[static_cast<std::size_t>(node_index)];
  const Eigen::Matrix4d xf = parent * node_transform(node);
  if (node.mesh >= 0) {
    if (static_cast<std::size_t>(node.mesh) >= model.meshes.size()) throw MeshFileError("mesh " + std::to_string(node.mesh) + " does not exist");
    for (const auto& prim : model.meshes[static_cast<std::size_t>(node.mesh)].primitives) append_primitive(model, prim, xf, mesh);
  }
  for (int child : node.children) append_node(model, child, xf, mesh, depth + 1, instances);
}

// glTF's external buffers and images are files named by URIs inside the file: they may only be
// files in the glTF file's own folder or below it (a pack is self-contained, and a mesh must not
// make us read what we were not given, e.g. "uri": "/etc/shadow" or "../../secret.bin").
struct GltfFolder {
  std::filesystem::path root;  // the glTF file's folder
};

bool inside(const std::string& file, const GltfFolder& folder) { return resolves_within(folder.root, file); }

// An outside file "exists", so that tinygltf goes on to read it and gltf_read_file says why not
// (tinygltf would otherwise report a plain "File not found").
bool gltf_file_exists(const std::string& file, void* user) {
  return !inside(file, *static_cast<GltfFolder*>(user)) || tinygltf::FileExists(file, nullptr);
}

bool gltf_read_file(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
  if (!inside(file, *static_cast<GltfFolder*>(user))) {
    if (err) *err += "'" + file + "' is outside the glTF file's folder\n";
    return false;
  }
  return tinygltf::ReadWholeFile(out, err, file, nullptr);
}

bool gltf_refuse_write(std::string* err, const std::string& file, const std::vector<unsigned char>&, void*) {
  if (err) *err += "'" + file + "': loading a glTF writes nothing\n";
  return false;
}

TriangleMesh<double> load_gltf(const std::filesystem::path& path, bool binary) {
  tinygltf::TinyGLTF loader;
  GltfFolder folder{path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path()};
  loader.SetFsCallbacks({&gltf_file_exists, &tinygltf::ExpandFilePath, &gltf_read_file, &gltf_refuse_write, &folder});
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  if (!ok) throw MeshFileError("cannot parse glTF: " + first_line(err.empty() ? warn : err));
  TriangleMesh<double> mesh;
  std::vector<int> roots;
  if (model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) < model.scenes.size()) {
    roots = model.scenes[static_cast<std::size_t>(model.defaultScene)].nodes;
  } else if (!model.scenes.empty()) {
    roots = model.scenes.front().nodes;
  } else {
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && static_cast<std::size_t>(c) < is_child.size()) is_child[static_cast<std::size_t>(c)] = true;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
  }
  std::size_t instances = 0;
  for (int r : roots) append_node(model, r, Eigen::Matrix4d::Identity(), mesh, 0, instances);
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
