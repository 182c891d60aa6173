// mesh_file_test.cpp — OBJ and glTF loading: content, transforms, and refusals.
#include <gtest/gtest.h>

#include <string>

#include "shadowref/scene/mesh_file.hpp"

namespace shadowref::scene {
namespace {

const std::filesystem::path kData = SHADOWREF_SCENE_TEST_DATA;

TEST(MeshFile, ObjQuadIsFanTriangulated) {
  const auto m = load_mesh_file(kData / "tri.obj");
  ASSERT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m.positions[2], Vec3<double>(1, 1, 0));
}

TEST(MeshFile, GltfAppliesNodeTransform) {
  const auto m = load_mesh_file(kData / "tri.gltf");
  ASSERT_EQ(m.triangles.size(), 1u);
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[0], Vec3<double>(0, 2, 0));  // translated by the node's (0, 2, 0)
  EXPECT_EQ(m.positions[2], Vec3<double>(0, 2, -1));
}

std::string error_of(const std::filesystem::path& p) {
  try {
    (void)load_mesh_file(p);
  } catch (const MeshFileError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MeshFile, Refusals) {
  EXPECT_EQ(error_of(kData / "missing.obj"), "no such file");
  EXPECT_EQ(error_of(kData / "bad_index.obj"), "face 1 of shape '' uses vertex 7 but the file has 3 vertices");
  EXPECT_EQ(error_of(kData / "empty.obj"), "the mesh has no triangles");
  EXPECT_EQ(error_of(kData / "lines.gltf"), "a primitive has mode 1, only TRIANGLES (4) is supported");
  EXPECT_EQ(error_of(kData / "not_a_mesh.ply"), "unknown mesh format '.ply' (expected .obj, .gltf or .glb)");
  EXPECT_EQ(error_of(kData), "no such file");  // a folder is not a mesh
}

TEST(MeshFile, NonFiniteObjVertexIsRefused) {
  // tinyobjloader alone reads "nan" as 0: load_mesh_file checks the coordinates' text first.
  EXPECT_EQ(error_of(kData / "nan.obj"), "vertex 2 is NaN or infinite");
}

}  // namespace
}  // namespace shadowref::scene
