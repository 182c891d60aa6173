// shadowref/scene/skin.hpp — a skinned object at its declared pose: glTF 2.0's linear blend skinning
// (glTF 2.0 specification, §3.7.3 "Skins"), written once for every producer: the scene loaders pose
// the mesh on the CPU with pose_vertex() (the reference and every CPU consumer see only the posed
// mesh), our renderer skins the bind pose in its vertex shader (renderer/shaders.cpp, the same sum),
// and the pack's scene.gltf carries the joints, inverse bind matrices, JOINTS_0 and WEIGHTS_0 so that
// an engine poses it itself. docs/scene-format.md, "Skins", says which pose is read.
//
// glTF's rule: a joint's matrix is jointMatrix_j = inverse(G_mesh) · G_joint_j · IBM_j (G: a node's
// global transform at the pose, IBM: the skin's inverse bind matrix, identity when absent), a vertex
// is posed as Σ_k weight_k · jointMatrix_{joint_k} · p_bind, and the mesh node's global transform
// G_mesh is then applied. The world position is therefore Σ_k weight_k · (G_joint · IBM) · p_bind:
// the mesh node's own transform cancels (glTF: "only the joint transforms are applied"). Here a
// joint's `world_from_bind` is that G_joint · IBM, with the scene object's transform in front.
// Weights are used as stored (glTF asks for a sum of 1; engines do not renormalise either).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "shadowref/conventions.hpp"

namespace shadowref::scene {

// Joints a skinned object may have (the renderer's uniform block holds this many matrices).
inline constexpr std::size_t kMaxSkinJoints = 128;

struct Skin {
  // Per vertex of the object's mesh, in the mesh's order: the bind-pose position as the file stores
  // it, four joint indices into `joints` and their four weights (≥ 0, not all 0).
  std::vector<Vec3<float>> bind_positions;
  std::vector<std::array<std::uint16_t, 4>> joint_indices;
  std::vector<std::array<float, 4>> weights;
  // Per joint at the pose: its world transform (the object's transform · G_joint) and its inverse
  // bind matrix. A rigid part of a mesh file beside a skinned one is a joint too (its node's
  // transform, identity IBM).
  struct Joint {
    Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
    Eigen::Matrix4d inverse_bind = Eigen::Matrix4d::Identity();
    Eigen::Matrix4d world_from_bind() const { return world * inverse_bind; }
  };
  std::vector<Joint> joints;
  // Where the bind pose lies in the world without its joints: the object's transform (a catalogue
  // scene's `transform`; identity in a glTF scene). Only a deliberately wrong render draws it.
  Eigen::Matrix4d bind_to_world = Eigen::Matrix4d::Identity();
};

// Vertex `i` of `skin` posed: Σ_k weight_k · world_from_bind(joint_k) · p_bind, in double.
Vec3<double> pose_vertex(const Skin& skin, std::size_t i);

}  // namespace shadowref::scene
