// shadowref/scene/mesh_file.hpp — triangle meshes from Wavefront OBJ (tinyobjloader) and glTF 2.0
// (tinygltf: .gltf with embedded or external buffers, and binary .glb).
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>

#include "shadowref/mesh.hpp"
#include "shadowref/scene/skin.hpp"

namespace shadowref::scene {

// Why a mesh file could not be used; what() is one line without the file name (the caller knows
// which file and which JSON path asked for it).
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// All triangles of the file as one mesh, in the file's own coordinates.
//   OBJ: every shape and group merged; polygons fan-triangulated (convex polygons assumed, as
//        the OBJ format does); normals, texture coordinates and materials ignored.
//   glTF: every TRIANGLES primitive reachable from the default scene (or from every root node
//        when there is none), node transforms applied, at the file's pose (docs/scene-format.md,
//        "Skins"): the first animation sampled at its extras.pose_time (else 0), skinned meshes
//        posed by linear blend skinning (skin.hpp).
// Throws MeshFileError for: a missing or unreadable file, an unknown extension, a parse error,
// an index out of range (checked before any vertex is touched), NaN or infinite coordinates (in
// OBJ also a coordinate that is missing or not a decimal number: tinyobjloader would read it as 0),
// glTF primitives in another mode than TRIANGLES, and a file with no triangle at all.
TriangleMesh<double> load_mesh_file(const std::filesystem::path& path);

// The same mesh, and for a glTF file with a skin the Skin it was posed with (its vertices in the
// mesh's order; rigid primitives beside skinned ones are joints of their own). `pose_time`, when
// given, replaces the file's own (the first animation's extras.pose_time). OBJ files and glTF
// files without a skin give no Skin.
struct PosedMesh {
  TriangleMesh<double> mesh;
  std::optional<Skin> skin;
};
PosedMesh load_posed_mesh_file(const std::filesystem::path& path, std::optional<double> pose_time = std::nullopt);

}  // namespace shadowref::scene
