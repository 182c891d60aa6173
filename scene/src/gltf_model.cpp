// gltf_model.cpp — opening and reading glTF files safely (gltf_model.hpp).
#include "gltf_model.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>

#include "shadowref/scene/path_within.hpp"

namespace shadowref::scene::detail {
namespace {

// glTF's external buffers and images are files named by URIs inside the file: they may only be
// files in the glTF file's own folder or below it (a pack is self-contained, and a glTF must not
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

// Images are not decoded here (the one PNG reader is outputs/image_io.hpp): an image read from a
// URI keeps its bytes; one in a buffer view keeps nothing, because tinygltf hands over its view's
// bytes without checking the view against its buffer (image_bytes() reads them, checked).
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                      int size, void*) {
  image->width = image->height = -1;
  image->component = image->bits = -1;
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

}  // namespace

std::string first_line(const std::string& text) {
  std::string s = text.substr(0, text.find('\n'));
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

tinygltf::Model open_gltf(const std::filesystem::path& path, bool binary, bool keep_json) {
  tinygltf::TinyGLTF loader;
  GltfFolder folder{path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path()};
  loader.SetFsCallbacks({&gltf_file_exists, &tinygltf::ExpandFilePath, &gltf_read_file, &gltf_refuse_write, &folder});
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  loader.SetStoreOriginalJSONForExtrasAndExtensions(keep_json);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  if (!ok) throw MeshFileError("cannot parse glTF: " + first_line(err.empty() ? warn : err));
  return model;
}

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

std::optional<std::size_t> shown_scene(const tinygltf::Model& model) {
  if (model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) < model.scenes.size())
    return static_cast<std::size_t>(model.defaultScene);
  if (!model.scenes.empty()) return 0;
  return std::nullopt;
}

std::vector<int> scene_roots(const tinygltf::Model& model) {
  if (const std::optional<std::size_t> at = shown_scene(model)) return model.scenes[*at].nodes;
  std::vector<int> roots;
  std::vector<bool> is_child(model.nodes.size(), false);
  for (const auto& n : model.nodes)
    for (int c : n.children)
      if (c >= 0 && static_cast<std::size_t>(c) < is_child.size()) is_child[static_cast<std::size_t>(c)] = true;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (!is_child[i]) roots.push_back(static_cast<int>(i));
  return roots;
}

const tinygltf::Node& walk_node(const tinygltf::Model& model, int node_index, int depth, std::size_t& instances) {
  if (node_index < 0 || static_cast<std::size_t>(node_index) >= model.nodes.size()) throw MeshFileError("node " + std::to_string(node_index) + " does not exist");
  if (depth > 64) throw MeshFileError("the node hierarchy is deeper than 64 (a cycle?)");
  if (++instances > kMaxNodeInstances)
    throw MeshFileError("the node hierarchy instances more than " + std::to_string(kMaxNodeInstances) +
                        " nodes (nodes referenced many times over)");
  return model.nodes[static_cast<std::size_t>(node_index)];
}

// Indices into the model are the file's word: check them (found by reliability/fuzz/gltf_fuzzer:
// vector::at's std::out_of_range used to escape as an uncaught exception).
const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    throw MeshFileError("accessor " + std::to_string(index) + " does not exist");
  return model.accessors[static_cast<std::size_t>(index)];
}

AccessorView view_accessor(const tinygltf::Model& model, int index, std::size_t element_size) {
  const auto& acc = accessor_at(model, index);
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

std::vector<Vec3<double>> primitive_positions(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                              const Eigen::Matrix4d& xf) {
  if (prim.mode != TINYGLTF_MODE_TRIANGLES) throw MeshFileError("a primitive has mode " + std::to_string(prim.mode) + ", only TRIANGLES (4) is supported");
  const auto pos_it = prim.attributes.find("POSITION");
  if (pos_it == prim.attributes.end()) throw MeshFileError("a primitive has no POSITION attribute");
  const auto& pos_acc = accessor_at(model, pos_it->second);
  if (pos_acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pos_acc.type != TINYGLTF_TYPE_VEC3) {
    throw MeshFileError("POSITION must be a float VEC3 accessor");
  }
  const AccessorView pos = view_accessor(model, pos_it->second, 3 * sizeof(float));
  std::vector<Vec3<double>> out;
  out.reserve(pos.count);
  for (std::size_t i = 0; i < pos.count; ++i) {
    float p[3];
    std::memcpy(p, pos.data + i * pos.stride, sizeof p);
    const Eigen::Vector4d w = xf * Eigen::Vector4d(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]), 1.0);
    const Vec3<double> q = w.head<3>() / w[3];
    if (!q.allFinite()) throw MeshFileError("vertex " + std::to_string(i) + " is NaN or infinite");
    out.push_back(q);
  }
  return out;
}

std::vector<std::uint32_t> primitive_indices(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                             std::size_t vertices) {
  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    const auto& acc = accessor_at(model, prim.indices);
    std::size_t size = 0;
    switch (acc.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
      default: throw MeshFileError("indices must be unsigned byte, short or int");
    }
    const AccessorView v = view_accessor(model, prim.indices, size);
    idx.reserve(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
      const unsigned char* e = v.data + i * v.stride;
      std::uint32_t x = 0;
      if (size == 1) x = *e;
      else if (size == 2) { std::uint16_t s; std::memcpy(&s, e, 2); x = s; }
      else std::memcpy(&x, e, 4);
      idx.push_back(x);
    }
  } else {
    for (std::size_t i = 0; i < vertices; ++i) idx.push_back(static_cast<std::uint32_t>(i));
  }
  if (idx.size() % 3 != 0) throw MeshFileError("a TRIANGLES primitive has " + std::to_string(idx.size()) + " indices, not a multiple of 3");
  for (const std::uint32_t i : idx)
    if (i >= vertices) throw MeshFileError("index " + std::to_string(i) + " is out of range (" + std::to_string(vertices) + " vertices)");
  return idx;
}

std::vector<float> read_float_attribute(const tinygltf::Model& model, int index, int components, int or_components,
                                        const std::string& what, int& got_components) {
  const auto& acc = accessor_at(model, index);
  const int n = acc.type == TINYGLTF_TYPE_SCALAR ? 1 : acc.type == TINYGLTF_TYPE_VEC2 ? 2 : acc.type == TINYGLTF_TYPE_VEC3 ? 3
              : acc.type == TINYGLTF_TYPE_VEC4 ? 4 : 0;
  if (n != components && (or_components == 0 || n != or_components))
    throw MeshFileError(what + " must have " + std::to_string(components) + (or_components ? " or " + std::to_string(or_components) : "") +
                        " components per element");
  std::size_t size = 0;
  switch (acc.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: size = 4; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
    default: throw MeshFileError(what + " must be float, or normalized unsigned byte or short");
  }
  if (size != 4 && !acc.normalized) throw MeshFileError(what + ": unsigned integer components must be normalized");
  const AccessorView v = view_accessor(model, index, size * static_cast<std::size_t>(n));
  std::vector<float> out;
  out.reserve(v.count * static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < v.count; ++i) {
    const unsigned char* e = v.data + i * v.stride;
    for (int k = 0; k < n; ++k) {
      float x = 0;
      if (size == 4) std::memcpy(&x, e + 4 * k, 4);
      else if (size == 1) x = static_cast<float>(e[k]) / 255.0f;
      else { std::uint16_t s; std::memcpy(&s, e + 2 * k, 2); x = static_cast<float>(s) / 65535.0f; }
      if (!std::isfinite(x)) throw MeshFileError(what + ": element " + std::to_string(i) + " is NaN or infinite");
      out.push_back(x);
    }
  }
  got_components = n;
  return out;
}

std::string image_bytes(const tinygltf::Model& model, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.images.size()) throw MeshFileError("image " + std::to_string(index) + " does not exist");
  const tinygltf::Image& image = model.images[static_cast<std::size_t>(index)];
  if (image.bufferView < 0) return std::string(image.image.begin(), image.image.end());
  if (static_cast<std::size_t>(image.bufferView) >= model.bufferViews.size())
    throw MeshFileError("image " + std::to_string(index) + ": buffer view " + std::to_string(image.bufferView) + " does not exist");
  const auto& bv = model.bufferViews[static_cast<std::size_t>(image.bufferView)];
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size()) throw MeshFileError("buffer view without a buffer");
  const auto& buf = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
  if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
    throw MeshFileError("image " + std::to_string(index) + " reads past the end of its buffer");
  return std::string(reinterpret_cast<const char*>(buf.data()) + bv.byteOffset, bv.byteLength);
}

}  // namespace shadowref::scene::detail
