// Unit tests of shadowref/primitives.hpp: every solid is closed, consistently wound outward,
// welded and free of degenerate triangles, with the documented counts.
#include "shadowref/primitives.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "scalar_types.hpp"
#include "shadowref/adjacency.hpp"

namespace shadowref {
namespace {

using test::eps;

template <class T>
class PrimitivesTest : public ::testing::Test {};
TYPED_TEST_SUITE(PrimitivesTest, test::FloatAndDouble);

// Six times the signed volume (divergence theorem): positive when the faces point outward.
template <class T>
double six_volume(const TriangleMesh<T>& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.positions[t[0]].template cast<double>().dot(
        m.positions[t[1]].template cast<double>().cross(m.positions[t[2]].template cast<double>()));
  return v;
}

template <class T>
void expect_clean_solid(const TriangleMesh<T>& m) {
  const auto adj = build_adjacency(m);
  ASSERT_TRUE(adj.ok()) << adj.message();
  EXPECT_TRUE(adj->report.closed_manifold());
  EXPECT_EQ(adj->report.degenerate_triangles, 0u);
  EXPECT_EQ(adj->report.welded_vertices, m.positions.size());  // welded: no repeated position
  // Euler characteristic V - E + F: 2 for a sphere-like solid, 0 for a torus (checked by callers).
  EXPECT_EQ(2 * adj->report.edges, 3 * m.triangles.size());  // closed: every edge has two faces
}

TYPED_TEST(PrimitivesTest, BoxIsACleanOutwardSolid) {
  using T = TypeParam;
  const auto m = make_box(Vec3<T>(-1, -2, -3), Vec3<T>(1, 2, 3));
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->positions.size(), 8u);
  EXPECT_EQ(m->triangles.size(), 12u);
  expect_clean_solid(*m);
  EXPECT_EQ(six_volume(*m), 6.0 * 48.0);  // 2 x 4 x 6, exact in both precisions
  // Face k is triangles 2k, 2k+1 in the order -x, +x, -y, +y, -z, +z: check the normals' signs.
  const int axis[6] = {0, 0, 1, 1, 2, 2};
  for (int f = 0; f < 6; ++f)
    for (int h = 0; h < 2; ++h) {
      const auto& t = m->triangles[2 * f + h];
      const Vec3<T> n = (m->positions[t[1]] - m->positions[t[0]]).cross(m->positions[t[2]] - m->positions[t[0]]);
      EXPECT_EQ(n[axis[f]] > T(0), f % 2 == 1) << "face " << f;
    }
}

TYPED_TEST(PrimitivesTest, UvSphereIsACleanOutwardSolid) {
  using T = TypeParam;
  const std::uint32_t seg = 24, rings = 12;
  const auto m = make_uv_sphere(T(2), seg, rings);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->positions.size(), 2 + (rings - 1) * seg);
  EXPECT_EQ(m->triangles.size(), 2 * seg * (rings - 1));
  expect_clean_solid(*m);
  const auto adj = build_adjacency(*m);
  EXPECT_EQ(int(m->positions.size()) - int(adj->report.edges) + int(m->triangles.size()), 2);
  // Every vertex at the radius: sin/cos of a rounded angle, scaled, then a sqrt: a few ulps.
  for (const auto& p : m->positions) EXPECT_CLOSE(p.norm(), T(2), eps<T>(8, T(2)));
  EXPECT_GT(six_volume(*m), 0.0);
}

TYPED_TEST(PrimitivesTest, TorusIsACleanOutwardSolidOfGenusOne) {
  using T = TypeParam;
  const auto m = make_torus(T(3), T(1), 32, 12);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->positions.size(), 32u * 12u);
  EXPECT_EQ(m->triangles.size(), 2u * 32u * 12u);
  expect_clean_solid(*m);
  const auto adj = build_adjacency(*m);
  EXPECT_EQ(int(m->positions.size()) - int(adj->report.edges) + int(m->triangles.size()), 0);
  EXPECT_GT(six_volume(*m), 0.0);
}

TYPED_TEST(PrimitivesTest, PlaneFacesUpAndIsOpen) {
  using T = TypeParam;
  const auto m = make_plane(T(5), T(3));
  ASSERT_TRUE(m.ok());
  for (const auto& t : m->triangles) {
    const Vec3<T> n = (m->positions[t[1]] - m->positions[t[0]]).cross(m->positions[t[2]] - m->positions[t[0]]);
    EXPECT_GT(n.y(), T(0));
  }
  const auto adj = build_adjacency(*m);
  EXPECT_EQ(adj->report.open_edges, 4u);
}

TYPED_TEST(PrimitivesTest, BadParametersAreRefused) {
  using T = TypeParam;
  EXPECT_EQ(make_box(Vec3<T>(0, 0, 0), Vec3<T>(1, 0, 1)).error(), Error::InvalidShape);
  EXPECT_EQ(make_box(Vec3<T>(0, 0, 0), Vec3<T>(1, std::numeric_limits<T>::infinity(), 1)).error(), Error::InvalidShape);
  EXPECT_EQ(make_uv_sphere(T(1), 2, 8).error(), Error::InvalidShape);
  EXPECT_EQ(make_uv_sphere(T(1), 8, 1).error(), Error::InvalidShape);
  EXPECT_EQ(make_uv_sphere(std::numeric_limits<T>::quiet_NaN(), 8, 8).error(), Error::InvalidShape);
  EXPECT_EQ(make_torus(T(1), T(1), 8, 8).error(), Error::InvalidShape);  // minor must be < major
  EXPECT_EQ(make_torus(T(2), T(1), 8, 2).error(), Error::InvalidShape);
  EXPECT_EQ(make_plane(T(0), T(1)).error(), Error::InvalidShape);
}

}  // namespace
}  // namespace shadowref
