// adjacency_index_buffer against the oracle meshopt_generateAdjacencyIndexBuffer (Debian's
// meshoptimizer) on closed, consistently wound meshes — where the far vertex across every edge is
// unique. Open edges are not compared: the two libraries document different conventions there.
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include "shadowref/adjacency.hpp"
#include "shadowref/primitives.hpp"
#include "test_meshes.hpp"

namespace shadowref {
namespace {

struct Case {
  const char* name;
  TriangleMesh<float> mesh;
};

std::vector<Case> closed_meshes() {
  return {{"cube", test::cube<float>()},
          {"split_cube", test::split_cube<float>()},
          {"uv_sphere", make_uv_sphere(1.0f, 24, 13).value()},
          {"torus", make_torus(2.0f, 0.75f, 36, 18).value()}};
}

TEST(AdjacencyMeshopt, MatchesOnClosedMeshes) {
  for (const Case& c : closed_meshes()) {
    SCOPED_TRACE(c.name);
    const auto adj = build_adjacency(c.mesh);
    ASSERT_TRUE(adj.ok());
    ASSERT_TRUE(adj->report.closed_manifold());
    std::vector<std::uint32_t> ours;
    adjacency_index_buffer(c.mesh, *adj, ours);

    std::vector<unsigned int> flat;
    for (const auto& t : c.mesh.triangles) flat.insert(flat.end(), t.begin(), t.end());
    std::vector<float> xyz;
    for (const auto& p : c.mesh.positions) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    std::vector<unsigned int> theirs(flat.size() * 2);
    meshopt_generateAdjacencyIndexBuffer(theirs.data(), flat.data(), flat.size(), xyz.data(), c.mesh.positions.size(),
                                         3 * sizeof(float));
    ASSERT_EQ(ours.size(), theirs.size());
    for (std::size_t i = 0; i < ours.size(); ++i) {
      // Even entries are the triangle itself in both. Odd entries: with split vertices the two may
      // name different copies of the same position, so the position is what must agree.
      EXPECT_EQ(c.mesh.positions[ours[i]], c.mesh.positions[theirs[i]]) << "entry " << i;
      if (c.mesh.positions.size() == adj->report.welded_vertices) {
        EXPECT_EQ(ours[i], theirs[i]) << "entry " << i;
      }
    }
  }
}

}  // namespace
}  // namespace shadowref
