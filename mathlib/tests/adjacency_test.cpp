// Unit tests of shadowref/adjacency.hpp: neighbours, the mesh report on clean and broken meshes,
// welding of split vertices, and the geometry-shader adjacency index buffer.
#include "shadowref/adjacency.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "scalar_types.hpp"
#include "shadowref/primitives.hpp"
#include "test_meshes.hpp"

namespace shadowref {
namespace {

template <class T>
class AdjacencyTest : public ::testing::Test {};
TYPED_TEST_SUITE(AdjacencyTest, test::FloatAndDouble);

// Neighbour relation is symmetric and the shared edge is the same welded pair.
template <class T>
void expect_symmetric_neighbours(const TriangleMesh<T>& m, const MeshAdjacency& adj) {
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int s = 0; s < 3; ++s) {
      const std::uint32_t n = adj.neighbors[t][s];
      if (n == kNoNeighbor) continue;
      const int ns = adj.neighbor_slots[t][s];
      EXPECT_EQ(adj.neighbors[n][ns], t);
      const auto& a = m.triangles[t];
      const auto& b = m.triangles[n];
      const std::uint32_t a0 = adj.weld[a[s]], a1 = adj.weld[a[(s + 1) % 3]];
      const std::uint32_t b0 = adj.weld[b[ns]], b1 = adj.weld[b[(ns + 1) % 3]];
      EXPECT_TRUE((a0 == b1 && a1 == b0) || (a0 == b0 && a1 == b1)) << "triangle " << t << " slot " << s;
    }
}

TYPED_TEST(AdjacencyTest, CubeIsClosedAndEveryEdgeHasANeighbour) {
  using T = TypeParam;
  const auto m = test::cube<T>();
  const auto adj = build_adjacency(m);
  ASSERT_TRUE(adj.ok());
  const MeshReport& r = adj->report;
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_EQ(r.welded_vertices, 8u);
  EXPECT_EQ(r.triangles, 12u);
  EXPECT_EQ(r.edges, 18u);  // 12 cube edges + 6 face diagonals
  EXPECT_EQ(r.open_edges, 0u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.miswound_edges, 0u);
  EXPECT_EQ(r.degenerate_triangles, 0u);
  EXPECT_TRUE(r.closed_manifold());
  for (const auto& n : adj->neighbors)
    for (std::uint32_t t : n) EXPECT_NE(t, kNoNeighbor);
  expect_symmetric_neighbours(m, *adj);
  // Triangles 0 and 1 (the -x face) share the diagonal 0-6: slot 2 of (0, 4, 6) is 6->0, slot 0 of
  // (0, 6, 2) is 0->6.
  EXPECT_EQ(adj->neighbors[0][2], 1u);
  EXPECT_EQ(adj->neighbors[1][0], 0u);
}

TYPED_TEST(AdjacencyTest, SphereAndTorusAreClosed) {
  using T = TypeParam;
  for (const auto& m : {make_uv_sphere(T(1), 16, 9).value(), make_torus(T(2), T(0.5), 20, 10).value()}) {
    const auto adj = build_adjacency(m);
    ASSERT_TRUE(adj.ok());
    EXPECT_TRUE(adj->report.closed_manifold());
    expect_symmetric_neighbours(m, *adj);
  }
}

TYPED_TEST(AdjacencyTest, OpenBoxReportsItsFourCracks) {
  using T = TypeParam;
  const auto m = test::open_box<T>();
  const auto adj = build_adjacency(m);
  ASSERT_TRUE(adj.ok());
  EXPECT_EQ(adj->report.open_edges, 4u);
  EXPECT_EQ(adj->report.edges, 17u);  // the top face's diagonal is gone
  EXPECT_EQ(adj->report.non_manifold_edges, 0u);
  EXPECT_EQ(adj->report.miswound_edges, 0u);
  EXPECT_FALSE(adj->report.closed_manifold());
  int no_neighbour = 0;
  for (const auto& n : adj->neighbors)
    for (std::uint32_t t : n) no_neighbour += t == kNoNeighbor;
  EXPECT_EQ(no_neighbour, 4);
}

TYPED_TEST(AdjacencyTest, FinMakesOneNonManifoldEdge) {
  using T = TypeParam;
  const auto m = test::cube_with_fin<T>();
  const auto adj = build_adjacency(m);
  ASSERT_TRUE(adj.ok());
  EXPECT_EQ(adj->report.non_manifold_edges, 1u);  // 6-7: top, front and fin
  EXPECT_EQ(adj->report.open_edges, 3u);          // the fin's outer edges
  EXPECT_EQ(adj->report.miswound_edges, 0u);
  EXPECT_FALSE(adj->report.closed_manifold());
  // The three triangles on edge 6-7 have no neighbour there.
  EXPECT_EQ(adj->neighbors[12][0], kNoNeighbor);  // fin (6, 7, 9), slot 0 = 6->7
}

TYPED_TEST(AdjacencyTest, MiswoundTriangleIsDetected) {
  using T = TypeParam;
  const auto m = test::miswound_cube<T>();
  const auto adj = build_adjacency(m);
  ASSERT_TRUE(adj.ok());
  EXPECT_EQ(adj->report.miswound_edges, 3u);
  EXPECT_EQ(adj->report.open_edges, 0u);
  EXPECT_EQ(adj->report.non_manifold_edges, 0u);
  EXPECT_FALSE(adj->report.closed_manifold());
  expect_symmetric_neighbours(m, *adj);  // mis-wound pairs are still neighbours
}

TYPED_TEST(AdjacencyTest, SplitVerticesAreWeldedForAdjacency) {
  using T = TypeParam;
  const auto m = test::split_cube<T>();
  const auto adj = build_adjacency(m);
  ASSERT_TRUE(adj.ok());
  EXPECT_EQ(adj->report.vertices, 36u);
  EXPECT_EQ(adj->report.welded_vertices, 8u);
  EXPECT_TRUE(adj->report.closed_manifold());
  expect_symmetric_neighbours(m, *adj);
}

TYPED_TEST(AdjacencyTest, DegenerateTrianglesAreReported) {
  using T = TypeParam;
  auto m = test::cube<T>();
  m.positions.emplace_back(0, 5, 0);                              // 8
  m.positions.emplace_back(T(1) / T(2), 5, 0);                     // 9
  m.positions.emplace_back(1, 5, 0);                              // 10: 8, 9, 10 collinear
  m.triangles.push_back({8, 9, 10});                               // zero area: keeps its edges
  m.triangles.push_back({3, 3, 5});                                // repeated vertex: no edges
  const auto adj = build_adjacency(m);
  ASSERT_TRUE(adj.ok());
  EXPECT_EQ(adj->report.degenerate_triangles, 2u);
  EXPECT_EQ(adj->report.open_edges, 3u);  // the collinear triangle's three edges
  EXPECT_EQ(adj->report.edges, 21u);
  EXPECT_EQ(adj->neighbors[13][0], kNoNeighbor);
  EXPECT_EQ(adj->degenerate_triangles, (std::vector<std::uint32_t>{12, 13}));
}

TYPED_TEST(AdjacencyTest, BadMeshesAreRefused) {
  using T = TypeParam;
  EXPECT_EQ(build_adjacency(TriangleMesh<T>{}).error(), Error::EmptyMesh);
  auto m = test::cube<T>();
  m.triangles[0][0] = 100;
  EXPECT_EQ(build_adjacency(m).error(), Error::IndexOutOfRange);
  m = test::cube<T>();
  m.positions[0].x() = std::numeric_limits<T>::quiet_NaN();
  EXPECT_EQ(build_adjacency(m).error(), Error::NonFinite);
}

TYPED_TEST(AdjacencyTest, IndexBufferEvenEntriesGiveBackTheTriangles) {
  using T = TypeParam;
  for (const auto& m : {test::cube<T>(), test::open_box<T>(), test::cube_with_fin<T>(), test::split_cube<T>(),
                        make_uv_sphere(T(1), 12, 7).value()}) {
    const auto adj = build_adjacency(m);
    ASSERT_TRUE(adj.ok());
    std::vector<std::uint32_t> ib;
    adjacency_index_buffer(m, *adj, ib);
    ASSERT_EQ(ib.size(), 6 * m.triangles.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(ib[6 * t + 2 * k], m.triangles[t][k]);
  }
}

TYPED_TEST(AdjacencyTest, IndexBufferFarVertexAndOpenEdgeConvention) {
  using T = TypeParam;
  // Cube: the far vertex across the -x diagonal 6->0 of (0, 4, 6) is 2, from (0, 6, 2).
  {
    const auto m = test::cube<T>();
    std::vector<std::uint32_t> ib;
    adjacency_index_buffer(m, build_adjacency(m).value(), ib);
    EXPECT_EQ(ib[5], 2u);
    // On a closed mesh every far vertex is off the edge and belongs to a triangle with the edge.
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int s = 0; s < 3; ++s) {
        const std::uint32_t far = ib[6 * t + 2 * s + 1];
        EXPECT_NE(far, m.triangles[t][s]);
        EXPECT_NE(far, m.triangles[t][(s + 1) % 3]);
        EXPECT_NE(far, m.triangles[t][(s + 2) % 3]);  // a real neighbour, not our own vertex
      }
  }
  // Open box: the 4 open edges get the triangle's own opposite vertex (the documented convention).
  {
    const auto m = test::open_box<T>();
    const auto adj = build_adjacency(m).value();
    std::vector<std::uint32_t> ib;
    adjacency_index_buffer(m, adj, ib);
    int own = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int s = 0; s < 3; ++s)
        if (adj.neighbors[t][s] == kNoNeighbor) {
          EXPECT_EQ(ib[6 * t + 2 * s + 1], m.triangles[t][(s + 2) % 3]);
          ++own;
        }
    EXPECT_EQ(own, 4);
  }
  // Mis-wound: the flipped triangle's edges get its own opposite vertex too.
  {
    const auto m = test::miswound_cube<T>();
    std::vector<std::uint32_t> ib;
    adjacency_index_buffer(m, build_adjacency(m).value(), ib);
    for (int s = 0; s < 3; ++s) EXPECT_EQ(ib[2 * s + 1], m.triangles[0][(s + 2) % 3]);
  }
}

}  // namespace
}  // namespace shadowref
