// Unit tests of shadowref/silhouette.hpp: facing with its tie rule, the hand cases (cube lit from
// above, open box, fin, mis-wound), orientation, multiplicity, and invalid lights.
#include "shadowref/silhouette.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "scalar_types.hpp"
#include "shadowref/primitives.hpp"
#include "test_meshes.hpp"

namespace shadowref {
namespace {

template <class T>
class SilhouetteTest : public ::testing::Test {};
TYPED_TEST_SUITE(SilhouetteTest, test::FloatAndDouble);

using Edges = std::vector<SilhouetteEdge>;

Edges sorted(Edges e) {
  std::sort(e.begin(), e.end(), [](auto a, auto b) { return std::pair(a.from, a.to) < std::pair(b.from, b.to); });
  return e;
}

template <class T>
Silhouette<T> silhouette_of(const TriangleMesh<T>& m, const Vec4<T>& light) {
  const auto caster = make_shadow_caster(m);
  EXPECT_TRUE(caster.ok());
  Silhouette<T> s;
  const auto n = find_silhouette(*caster, light, s);
  EXPECT_TRUE(n.ok()) << n.message();
  return s;
}

TYPED_TEST(SilhouetteTest, CubeLitFromAboveHasTheTopSquareOrientedOutward) {
  using T = TypeParam;
  const auto s = silhouette_of(test::cube<T>(), Vec4<T>(T(0.2), 10, T(0.1), 1));
  EXPECT_EQ(s.lit_count, 2u);  // the two top triangles
  // The top face walks 2 -> 6 -> 7 -> 3 (counter-clockwise from above); its silhouette edges are
  // walked the other way, so that the side quads (from, to, to', from') face out.
  EXPECT_EQ(sorted(s.edges), sorted(Edges{{6, 2}, {7, 6}, {3, 7}, {2, 3}}));
  // The same light scaled homogeneously (w = 2) is the same point: same answer.
  EXPECT_EQ(sorted(silhouette_of(test::cube<T>(), Vec4<T>(T(0.4), 20, T(0.2), 2)).edges), sorted(s.edges));
}

TYPED_TEST(SilhouetteTest, SideQuadOfATopEdgeFacesOut) {
  using T = TypeParam;
  // Edge (6, 2) lies on x = -1; its quad (6, 2, 2', 6') must face -x. With the light straight
  // above x = 0, 2' = 2 + t (2 - L): the normal (2 - 6) x (2' - 6) has a negative x.
  const auto m = test::cube<T>();
  const Vec3<T> l(0, 10, 0);
  const Vec3<T> far2 = m.positions[2] + T(100) * (m.positions[2] - l);
  const Vec3<T> n = (m.positions[2] - m.positions[6]).cross(far2 - m.positions[6]);
  EXPECT_LT(n.x(), T(0));
}

TYPED_TEST(SilhouetteTest, DirectionalFromStraightAboveUsesTheTieRule) {
  using T = TypeParam;
  // The side faces contain the light direction (plane . L = 0): lit by the tie rule, so the lit
  // region is top + sides and the silhouette is the BOTTOM square, walked as the bottom face
  // (0 -> 1 -> 5 -> 4) walks it. The volume is the same solid either way.
  const auto s = silhouette_of(test::cube<T>(), Vec4<T>(0, 1, 0, 0));
  EXPECT_EQ(s.lit_count, 10u);
  EXPECT_EQ(sorted(s.edges), sorted(Edges{{0, 1}, {1, 5}, {5, 4}, {4, 0}}));
}

TYPED_TEST(SilhouetteTest, OpenEdgeOfALitFaceIsASilhouette) {
  using T = TypeParam;
  const Vec4<T> light(10, 10, T(0.3), 1);  // lights +x and +y of the closed cube
  const auto closed = silhouette_of(test::cube<T>(), light);
  EXPECT_EQ(closed.lit_count, 4u);
  EXPECT_EQ(closed.edges.size(), 6u);
  EXPECT_EQ(std::count(closed.edges.begin(), closed.edges.end(), SilhouetteEdge{7, 3}), 0);
  // Without the top face, +x is the only lit face and its open top edge 3 -> 7 is a silhouette.
  const auto open = silhouette_of(test::open_box<T>(), light);
  EXPECT_EQ(open.lit_count, 2u);
  EXPECT_EQ(sorted(open.edges), sorted(Edges{{7, 3}, {5, 7}, {1, 5}, {3, 1}}));
}

TYPED_TEST(SilhouetteTest, FinContributesItsOpenEdgesAndCancelsOnTheSharedEdge) {
  using T = TypeParam;
  // The fin faces (0, -1, 1); this light lights it and the cube's front (+z) face. On edge 6-7 the
  // fin walks 6 -> 7 and the front face 7 -> 6: net 0, no quad. The fin's open edges and the front
  // face's three other edges remain.
  const auto s = silhouette_of(test::cube_with_fin<T>(), Vec4<T>(T(0.3), T(0.2), 10, 1));
  EXPECT_EQ(s.lit_count, 4u);
  EXPECT_EQ(sorted(s.edges), sorted(Edges{{9, 7}, {8, 9}, {6, 8}, {5, 4}, {7, 5}, {4, 6}}));
}

TYPED_TEST(SilhouetteTest, MiswoundEdgeWithTwoLitFacesCountsTwice) {
  using T = TypeParam;
  // Triangle 0 walked backwards, (0, 6, 4), faces +x as wound; this light lights it and the +z
  // face, which both walk 6 -> 4: the edge has multiplicity 2 (two prisms share that side).
  const auto s = silhouette_of(test::miswound_cube<T>(), Vec4<T>(T(0.5), T(0.3), 10, 1));
  EXPECT_EQ(std::count(s.edges.begin(), s.edges.end(), SilhouetteEdge{4, 6}), 2);
}

// On a closed, consistently wound mesh the silhouette is a set of closed loops: at every welded
// vertex as many edges leave as arrive, and every edge has one lit and one unlit face.
TYPED_TEST(SilhouetteTest, ClosedMeshesGiveClosedLoopsBetweenLitAndUnlitFaces) {
  using T = TypeParam;
  const std::vector<TriangleMesh<T>> meshes{make_uv_sphere(T(1), 32, 17).value(), make_torus(T(2), T(0.6), 40, 16).value(),
                                            test::split_cube<T>()};
  const std::vector<Vec4<T>> lights{Vec4<T>(3, 4, 5, 1), Vec4<T>(T(0.3), T(0.9), T(1.5), 1), Vec4<T>(1, 2, -3, 0),
                                    Vec4<T>(0, 5, T(0.01), 1)};
  for (const auto& m : meshes) {
    const auto caster = make_shadow_caster(m).value();
    Silhouette<T> s;
    for (const auto& l : lights) {
      ASSERT_TRUE(find_silhouette(caster, l, s).ok());
      EXPECT_FALSE(s.edges.empty());
      std::map<std::uint32_t, int> balance;
      for (const auto& e : s.edges) {
        ++balance[caster.adjacency.weld[e.from]];
        --balance[caster.adjacency.weld[e.to]];
      }
      for (const auto& [v, b] : balance) EXPECT_EQ(b, 0) << "vertex " << v;
    }
  }
}

TYPED_TEST(SilhouetteTest, EveryFaceUnlitOrLitGivesNoSilhouette) {
  using T = TypeParam;
  // A light inside the closed cube sees every face's back: nothing lit, nothing cast.
  const auto s = silhouette_of(test::cube<T>(), Vec4<T>(T(0.1), T(0.2), T(0.3), 1));
  EXPECT_EQ(s.lit_count, 0u);
  EXPECT_TRUE(s.edges.empty());
}

TYPED_TEST(SilhouetteTest, DegenerateFacesAreNeverLit) {
  using T = TypeParam;
  auto m = test::cube<T>();
  m.triangles.push_back({0, 1, 1});
  const auto s = silhouette_of(m, Vec4<T>(1, 0, 0, 0));  // plane . L = 0 for a zero plane
  EXPECT_EQ(s.lit[12], 0);
}

TYPED_TEST(SilhouetteTest, InvalidLightsAreRefused) {
  using T = TypeParam;
  const auto caster = make_shadow_caster(test::cube<T>()).value();
  Silhouette<T> s;
  EXPECT_EQ(find_silhouette(caster, Vec4<T>(0, 0, 0, 0), s).error(), Error::ZeroLight);
  EXPECT_EQ(find_silhouette(caster, Vec4<T>(0, 5, 0, -1), s).error(), Error::NegativeLightW);
  EXPECT_EQ(find_silhouette(caster, Vec4<T>(0, std::numeric_limits<T>::quiet_NaN(), 0, 1), s).error(), Error::NonFinite);
}

// The flat edge pass (regular edges by their two faces, irregular ones by their uses) gives the
// edges, in order, that walking every edge by its uses gives.
TYPED_TEST(SilhouetteTest, FlatEdgePassEqualsTheWalkOverAllEdges) {
  using T = TypeParam;
  auto fin_and_crack = test::cube_with_fin<T>();
  fin_and_crack.triangles.erase(fin_and_crack.triangles.begin() + 2);  // an open −x edge too
  // Large enough for whole edge blocks to be skipped (all their faces lit, or all unlit), with
  // irregular edges among them: four holes (one by the south pole, in the last edge block) and a
  // fin.
  auto holed = make_uv_sphere(T(1), 120, 61).value();
  for (std::size_t t : {14395u, 7000u, 3001u, 50u}) holed.triangles.erase(holed.triangles.begin() + static_cast<std::ptrdiff_t>(t));
  holed.triangles.push_back(holed.triangles[4000]);
  const std::vector<TriangleMesh<T>> meshes{test::open_box<T>(),   test::cube_with_fin<T>(), test::miswound_cube<T>(),
                                            test::split_cube<T>(), fin_and_crack,            make_uv_sphere(T(1), 40, 21).value(),
                                            holed};
  const std::vector<Vec4<T>> lights{Vec4<T>(3, 4, 5, 1), Vec4<T>(T(0.3), T(0.2), 10, 1), Vec4<T>(1, 2, -3, 0),
                                    Vec4<T>(-10, T(0.5), -1, 1), Vec4<T>(T(0.5), -10, T(0.3), 1)};
  for (const auto& m : meshes) {
    const auto caster = make_shadow_caster(m).value();
    Silhouette<T> s;
    for (const auto& l : lights) {
      ASSERT_TRUE(find_silhouette(caster, l, s).ok());
      Edges walked;
      for (std::size_t e = 0; e < caster.adjacency.edge_count(); ++e)
        silhouette_detail::emit_edge(caster, s.lit.data(), e, walked);
      EXPECT_EQ(s.edges, walked) << "light " << l.transpose();
    }
  }
}

// The SoA facing loop sums plane · L in Eigen's order: the same sign as face_planes[t].dot(L),
// bit for bit, also for products that nearly cancel.
TYPED_TEST(SilhouetteTest, FacingMatchesTheVec4Dot) {
  using T = TypeParam;
  TriangleMesh<T> m;
  std::uint32_t seed = 12345;
  const auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    return T(static_cast<std::int32_t>(seed >> 8) - (1 << 23)) / T(1 << 20);  // [-8, 8)
  };
  for (std::uint32_t t = 0; t < 3000; ++t) {
    for (int k = 0; k < 3; ++k) m.positions.emplace_back(next(), next(), next());
    m.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  const auto caster = make_shadow_caster(m).value();
  Silhouette<T> s;
  for (int i = 0; i < 20; ++i) {
    // Lights on (or next to) the planes of some faces: the dot is a cancellation there.
    const Vec3<T>& p = m.positions[static_cast<std::size_t>(97 * i)];
    const Vec4<T> l = i % 2 ? Vec4<T>(p.x(), p.y(), p.z(), 1) : Vec4<T>(next(), next(), next(), i % 4 ? T(1) : T(0));
    ASSERT_TRUE(find_silhouette(caster, l, s).ok());
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      ASSERT_EQ(s.lit[t], caster.face_planes[t].dot(l) >= T(0) ? 1 : 0) << "face " << t << " light " << i;
  }
}

TYPED_TEST(SilhouetteTest, BuffersAreReusedAcrossLights) {
  using T = TypeParam;
  const auto caster = make_shadow_caster(make_uv_sphere(T(1), 32, 17).value()).value();
  Silhouette<T> s;
  ASSERT_TRUE(find_silhouette(caster, Vec4<T>(3, 4, 5, 1), s).ok());
  s.edges.reserve(4 * s.edges.size());
  const auto* lit = s.lit.data();
  const auto* edges = s.edges.data();
  ASSERT_TRUE(find_silhouette(caster, Vec4<T>(-3, 1, 2, 1), s).ok());
  EXPECT_EQ(s.lit.data(), lit);  // no reallocation for the second light
  EXPECT_EQ(s.edges.data(), edges);
}

#if defined(__x86_64__) && !defined(__AVX2__)
// The AVX2 facing loop (eight faces per register) gives the SSE2 loop's answer bit for bit: planes
// and lights with mixed signs and magnitudes, exact zeros and ties among them (a product that
// rounds the other way, or a fused multiply-add, would flip some of these).
TEST(ClassifyFaces, TheAvx2LoopIsTheScalarLoopBitForBit) {
  if (!cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2: that path is not taken";
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_int_distribution<int> e(-30, 30), pick(0, 9);
  const std::size_t n = 4099;  // not a multiple of 8: the loop's tail too
  std::vector<float> x(n), y(n), z(n), w(n);
  for (std::size_t t = 0; t < n; ++t)
    for (auto* a : {&x, &y, &z, &w}) {
      const int k = pick(rng);
      (*a)[t] = k == 0 ? 0.0f : k == 1 ? -0.0f : k == 2 ? 1.0f : std::ldexp(u(rng), e(rng));
    }
  // Faces whose sign depends on the order of the sums under the light (1, 1, 1, 1): 1 + tiny
  // rounds to 1, so (x + z) + (y + w) = 0 (lit) where (x + y) + (z + w) = −tiny (not lit).
  for (std::size_t t = 0; t < 64; ++t) {
    x[t] = std::ldexp(1.0f, static_cast<int>(t % 8)), y[t] = -x[t];
    z[t] = (t % 2 ? -1.0f : 1.0f) * std::ldexp(1.0f, -30 + static_cast<int>(t % 8)), w[t] = t % 3 ? 0.0f : -z[t];
  }
  for (int trial = 0; trial < 50; ++trial) {
    float lx = u(rng), ly = u(rng), lz = trial % 5 == 0 ? 0.0f : u(rng), lw = trial % 2 ? 1.0f : 0.0f;
    if (trial == 0) lx = ly = lz = lw = 1.0f;
    std::vector<std::uint8_t> avx(n, 7);
    const std::size_t count = silhouette_detail::classify_avx2(x.data(), y.data(), z.data(), w.data(), lx, ly, lz, lw,
                                                               avx.data(), n);
    std::size_t expected_count = 0;
    for (std::size_t t = 0; t < n; ++t) {
      const float d = (x[t] * lx + z[t] * lz) + (y[t] * ly + w[t] * lw);
      const std::uint8_t l = d >= 0.0f;
      expected_count += l;
      ASSERT_EQ(avx[t], l) << "face " << t << ", trial " << trial;
    }
    EXPECT_EQ(count, expected_count);
  }
}
#endif

}  // namespace
}  // namespace shadowref
