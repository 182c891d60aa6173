// gltf_model.hpp (private) — a glTF 2.0 file opened with tinygltf and read safely: the file's
// external buffers and images confined to its folder, node transforms, the scene's root nodes, and
// accessors read with every index and byte range checked before it is touched. Shared by the mesh
// reader (mesh_file.cpp) and the whole-scene reader (gltf_scene.cpp).
//
// Every refusal is a MeshFileError whose what() is one line without the file name (the caller
// knows the file).
#pragma once

#include <tiny_gltf.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shadowref/conventions.hpp"
#include "shadowref/scene/mesh_file.hpp"
#include "shadowref/scene/skin.hpp"

namespace shadowref::scene::detail {

// Opens `path` (.gltf, or binary .glb when `binary`). External buffer and image files must lie in
// the glTF file's folder or below it; nothing is written. Images are not decoded: an image given by
// a URI keeps its file's bytes in Image::image (width and height -1); an image in a buffer view
// keeps nothing (read it with image_bytes()). With `keep_json`, every extras and extensions object
// keeps its JSON text (extras_json_string), for readers that check it key by key.
tinygltf::Model open_gltf(const std::filesystem::path& path, bool binary, bool keep_json = false);

// The first line of a multi-line message (tinygltf's errors end in newlines).
std::string first_line(const std::string& text);

// The node's local transform: its matrix (column-major), or T * R * S from its translation,
// rotation and scale.
Eigen::Matrix4d node_transform(const tinygltf::Node& node);

// The root nodes of the default scene, else of the first scene, else every node that is no node's
// child.
// The scene a file shows: the default scene, else the first; nullopt when it lists none.
std::optional<std::size_t> shown_scene(const tinygltf::Model& model);
std::vector<int> scene_roots(const tinygltf::Model& model);

// A hierarchy that names the same node many times over (node i's children [i+1, i+1], 60 deep) is
// small on disk and 2^60 instances when walked: a walk stops at this many node instances.
inline constexpr std::size_t kMaxNodeInstances = std::size_t{1} << 20;

// Checks one step of a walk: `node_index` exists, `depth` is at most 64 and the walk has not passed
// kMaxNodeInstances (counted in `instances`). Returns the node.
const tinygltf::Node& walk_node(const tinygltf::Model& model, int node_index, int depth, std::size_t& instances);

// Accessor `index`, which must exist.
const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index);

// The bytes of accessor `index` as (pointer to element 0, stride, count), the whole range checked
// against its buffer view and buffer.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
};
AccessorView view_accessor(const tinygltf::Model& model, int index, std::size_t element_size);

// A TRIANGLES primitive's POSITION (a float VEC3 accessor) through `xf`, in double; refuses another
// mode, a missing POSITION and NaN or infinite results.
std::vector<Vec3<double>> primitive_positions(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                              const Eigen::Matrix4d& xf);

// The primitive's triangles as indices into its `vertices` vertices (its index accessor, unsigned
// byte, short or int; or 0, 1, 2, … without one): a multiple of 3, every index in range.
std::vector<std::uint32_t> primitive_indices(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                             std::size_t vertices);

// Accessor `index` as `components` floats per element (1 to 4): float components as they are,
// unsigned byte and short ones when normalized (value / 255, / 65535: glTF's TEXCOORD_n and
// COLOR_n), others refused; the type must have `components` components (or, when `or_components`
// is non-zero, that many: COLOR_0 is VEC3 or VEC4). `what` names the attribute in messages.
// Returns count × (the accessor's components) floats.
std::vector<float> read_float_attribute(const tinygltf::Model& model, int index, int components, int or_components,
                                        const std::string& what, int& got_components);

// The bytes of image `index`: those tinygltf read from its URI (open_gltf keeps them), or its
// buffer view's, range checked.
std::string image_bytes(const tinygltf::Model& model, int index);

// ---- The pose (gltf_skin.cpp; docs/scene-format.md, "Skins")

// The time the first animation is sampled at: its `extras.pose_time` (seconds, finite, ≥ 0), else 0.
double pose_time(const tinygltf::Model& model);

// Every node's local transform at the pose: its matrix or TRS, with the first animation's channels
// sampled at `time` (glTF 2.0 §3.11: STEP, LINEAR with spherical linear interpolation of rotations,
// CUBICSPLINE; before the first key the first value, after the last the last). Refuses an animated
// node that has a `matrix`, a channel of morph weights, and malformed samplers. Other animations are
// not read (the caller says so).
std::vector<Eigen::Matrix4d> posed_local_transforms(const tinygltf::Model& model, double time);

// Every node's global transform from `locals` (its parent's global times its local; a node that is
// no node's child is a root). Refuses a hierarchy deeper than 64.
std::vector<Eigen::Matrix4d> global_transforms(const tinygltf::Model& model, const std::vector<Eigen::Matrix4d>& locals);

// Builds one Skin (skin.hpp) from primitives: skinned ones by their node's skin, rigid ones as a
// joint of their own (their node's global transform), so that a mesh file mixing both is one skin.
class SkinBuilder {
 public:
  SkinBuilder(const tinygltf::Model& model, const std::vector<Eigen::Matrix4d>& globals) : model_(model), globals_(globals) {}
  // Appends the primitive's vertices skinned by skin `skin` (JOINTS_0, WEIGHTS_0 and the skin's
  // inverse bind matrices checked) and returns them posed, in world space.
  std::vector<Vec3<double>> add_skinned(const tinygltf::Primitive& prim, int skin);
  // Appends the primitive's vertices as one rigid joint at `xf`; returns them through `xf`.
  std::vector<Vec3<double>> add_rigid(const tinygltf::Primitive& prim, const Eigen::Matrix4d& xf);
  Skin take() { return std::move(skin_); }

 private:
  std::size_t add_joint(const Skin::Joint& joint);
  const tinygltf::Model& model_;
  const std::vector<Eigen::Matrix4d>& globals_;
  std::vector<std::pair<int, std::size_t>> skin_offsets_;  // (skin index, its first joint in skin_)
  Skin skin_;
};

}  // namespace shadowref::scene::detail
