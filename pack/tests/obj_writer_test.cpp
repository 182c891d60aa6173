// obj_writer_test.cpp — an object's OBJ text: every position exactly, 1-based counter-clockwise faces,
// read back by the scene's own mesh reader (tinyobjloader) as the same triangles.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "shadowref/pack/obj_writer.hpp"
#include "shadowref/pack/scene_files.hpp"
#include "shadowref/scene/mesh_file.hpp"

namespace shadowref::pack {
namespace {

scene::Object triangle_pair() {
  scene::Object o;
  o.name = "pair";
  // 0.1f has no short decimal: %.9g must still give back the very float.
  o.mesh.positions = {{0.1f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, -2.5f}, {1.0f, 1.0f, 1e-7f}};
  o.mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
  return o;
}

TEST(ObjWriter, WritesOneBasedFacesAndExactPositions) {
  const std::string t = obj_text(triangle_pair());
  EXPECT_NE(t.find("\no pair\n"), std::string::npos);
  EXPECT_NE(t.find("\nf 1 2 3\nf 2 4 3\n"), std::string::npos) << t;
  EXPECT_NE(t.find("\nv 0.100000001 0 0\n"), std::string::npos) << t;
}

TEST(ObjWriter, TheMeshReaderReadsBackTheSameTriangles) {
  const scene::Object o = triangle_pair();
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("shadowref_obj_writer_" + std::to_string(::getpid()) + ".obj");
  std::ofstream(file) << obj_text(o);
  const TriangleMesh<double> back = scene::load_mesh_file(file);
  std::filesystem::remove(file);
  ASSERT_EQ(back.triangles.size(), o.mesh.triangles.size());
  for (std::size_t t = 0; t < back.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto& a = back.positions[back.triangles[t][static_cast<std::size_t>(k)]];
      const auto& b = o.mesh.positions[o.mesh.triangles[t][static_cast<std::size_t>(k)]];
      EXPECT_EQ(static_cast<float>(a.x()), b.x());
      EXPECT_EQ(static_cast<float>(a.y()), b.y());
      EXPECT_EQ(static_cast<float>(a.z()), b.z());
    }
}

TEST(SceneFiles, SafeNameKeepsOnlyPortableCharacters) {
  EXPECT_EQ(safe_name("ball-2_x"), "ball-2_x");
  EXPECT_EQ(safe_name("a b/c.d"), "a_b_c_d");
}

}  // namespace
}  // namespace shadowref::pack
