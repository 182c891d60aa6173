// Unit tests of shadowref/mesh.hpp: validation and the welding of equal positions.
#include "shadowref/mesh.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "scalar_types.hpp"
#include "test_meshes.hpp"

namespace shadowref {
namespace {

template <class T>
class MeshTest : public ::testing::Test {};
TYPED_TEST_SUITE(MeshTest, test::Scalars);

TYPED_TEST(MeshTest, ValidMeshHasNoError) {
  using T = TypeParam;
  EXPECT_FALSE(validate_mesh(test::cube<T>()).has_value());
}

TYPED_TEST(MeshTest, EmptyMeshIsRefused) {
  using T = TypeParam;
  TriangleMesh<T> m;
  m.positions.emplace_back(0, 0, 0);
  EXPECT_EQ(validate_mesh(m), Error::EmptyMesh);
}

TYPED_TEST(MeshTest, OutOfRangeIndexIsRefused) {
  using T = TypeParam;
  TriangleMesh<T> m = test::cube<T>();
  m.triangles[5][2] = 8;  // the cube has vertices 0..7
  EXPECT_EQ(validate_mesh(m), Error::IndexOutOfRange);
}

TYPED_TEST(MeshTest, NonFiniteUsedPositionIsRefusedUnusedIsNot) {
  using T = TypeParam;
  TriangleMesh<T> m = test::cube<T>();
  m.positions.emplace_back(std::numeric_limits<T>::quiet_NaN(), 0, 0);  // vertex 8, unused
  EXPECT_FALSE(validate_mesh(m).has_value());
  m.positions[3].y() = std::numeric_limits<T>::infinity();
  EXPECT_EQ(validate_mesh(m), Error::NonFinite);
}

TYPED_TEST(MeshTest, WeldMapPointsEveryCopyAtTheFirstIndex) {
  using T = TypeParam;
  std::vector<Vec3<T>> p{Vec3<T>(1, 2, 3), Vec3<T>(0, 0, 0), Vec3<T>(1, 2, 3), Vec3<T>(-0.0, 0, 0),
                         Vec3<T>(1, 2, T(3) + std::numeric_limits<T>::epsilon() * T(4))};
  const auto map = weld_map(p);
  // 0 and 2 equal; 1 and 3 equal (-0 == +0); 4 differs from 0 by one ulp of 3 (exact welding).
  EXPECT_EQ(map, (std::vector<std::uint32_t>{0, 1, 0, 1, 4}));
}

// NaN equals nothing: an (unused) NaN position is its own representative, and the others still
// weld to their smallest index around it (a sort by coordinates breaks here: NaN has no order).
TYPED_TEST(MeshTest, WeldMapKeepsNaNApartAndWeldsAroundIt) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  std::vector<Vec3<T>> p;
  for (int i = 0; i < 40; ++i)  // x NaN for every third; z -0 or +0 (they weld)
    p.emplace_back(i % 3 == 0 ? nan : T(i % 5), T(i % 2), i % 4 == 0 ? -T(0) : T(0));
  const auto map = weld_map(p);
  for (std::size_t v = 0; v < p.size(); ++v) {
    std::uint32_t first = static_cast<std::uint32_t>(v);
    for (std::size_t u = 0; u < v; ++u)
      if (p[u] == p[v]) {
        first = static_cast<std::uint32_t>(u);
        break;
      }
    EXPECT_EQ(map[v], first) << "vertex " << v;
  }
}

TYPED_TEST(MeshTest, WeldOfSplitCubeGivesTheCube) {
  using T = TypeParam;
  const TriangleMesh<T> split = test::split_cube<T>();
  ASSERT_EQ(split.positions.size(), 36u);
  std::vector<std::uint32_t> remap;
  const TriangleMesh<T> w = weld(split, &remap);
  EXPECT_EQ(w.positions.size(), 8u);
  ASSERT_EQ(w.triangles.size(), split.triangles.size());
  for (std::size_t t = 0; t < w.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(w.positions[w.triangles[t][k]], split.positions[split.triangles[t][k]]);  // same corner, same order
      EXPECT_EQ(remap[split.triangles[t][k]], w.triangles[t][k]);
    }
}

}  // namespace
}  // namespace shadowref
