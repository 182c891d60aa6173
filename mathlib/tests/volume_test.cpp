// Unit tests of shadowref/volume.hpp: buffer layout (only the used vertices), extrusion formulas, caps and their winding,
// closedness, the directional single apex, finite extrusion and degenerate input.
#include "shadowref/volume.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include "scalar_types.hpp"
#include "shadowref/primitives.hpp"
#include "test_meshes.hpp"

namespace shadowref {
namespace {

using test::eps;

template <class T>
class VolumeTest : public ::testing::Test {};
TYPED_TEST_SUITE(VolumeTest, test::FloatAndDouble);

template <class T>
struct Built {
  ShadowCaster<T> caster;
  Silhouette<T> sil;
  ShadowVolume<T> vol;
};

template <class T>
Built<T> build(const TriangleMesh<T>& m, const Vec4<T>& light, const VolumeOptions<T>& opt = {}) {
  Built<T> b{make_shadow_caster(m).value(), {}, {}};
  EXPECT_TRUE(find_silhouette(b.caster, light, b.sil).ok());
  const auto r = build_shadow_volume(b.caster, b.sil, opt, b.vol);
  EXPECT_TRUE(r.ok()) << r.message();
  return b;
}

// Every directed edge (i, j) of the index buffer is matched by a (j, i): a closed surface whose
// triangles are consistently oriented (on vertex indices; the meshes here are welded).
::testing::AssertionResult closed_and_consistent(const std::vector<std::uint32_t>& idx) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++count[{idx[t + k], idx[t + (k + 1) % 3]}];
  for (const auto& [e, c] : count) {
    const auto it = count.find({e.second, e.first});
    const int back = it == count.end() ? 0 : it->second;
    if (back != c)
      return ::testing::AssertionFailure() << "edge " << e.first << "->" << e.second << " used " << c << " times, its reverse "
                                           << back << " times";
  }
  return ::testing::AssertionSuccess();
}

TYPED_TEST(VolumeTest, ExtrusionFormulas) {
  using T = TypeParam;
  // (V.xyz L.w - L.xyz V.w, 0): exact in these small integers.
  EXPECT_EQ(extrude_to_infinity(Vec4<T>(1, 2, 3, 1), Vec4<T>(0, 10, 0, 1)), Vec4<T>(1, -8, 3, 0));
  EXPECT_EQ(extrude_to_infinity(Vec4<T>(1, 2, 3, 1), Vec4<T>(0, 1, 0, 0)), Vec4<T>(0, -1, 0, 0));
  // Finite: 3 units along (p - L) / |p - L| = (0, -1, 0)... from (0, 2, 0) with the light at y = 10.
  EXPECT_EQ(extrude_finite(Vec3<T>(0, 2, 0), Vec4<T>(0, 10, 0, 1), T(3)), Vec4<T>(0, -1, 0, 1));
  // A 3-4-5 direction: one division and a product per coordinate, a few ulps of the result's scale.
  const Vec4<T> f = extrude_finite(Vec3<T>(3, 4, 0), Vec4<T>(0, 0, 0, 1), T(5));
  EXPECT_CLOSE(f.x(), T(6), eps<T>(4, T(6)));
  EXPECT_CLOSE(f.y(), T(8), eps<T>(4, T(8)));
  // At the light: no direction, the point stays.
  EXPECT_EQ(extrude_finite(Vec3<T>(1, 1, 1), Vec4<T>(1, 1, 1, 1), T(5)), Vec4<T>(1, 1, 1, 1));
}

// The mesh vertices the index buffer uses, each once (a set).
template <class T>
std::set<std::uint32_t> used_mesh_vertices(const ShadowVolume<T>& vol) {
  std::set<std::uint32_t> used;
  const bool apex = vol.vertices.size() == vol.source.size() + 1;
  for (std::uint32_t i : vol.indices)
    if (apex ? i < vol.source.size() : true) used.insert(vol.source[apex ? i : i / 2]);
  return used;
}

TYPED_TEST(VolumeTest, PointLightInfiniteLayout) {
  using T = TypeParam;
  const auto m = test::cube<T>();
  const Vec4<T> light(T(0.2), 10, T(0.1), 1);
  const auto b = build(m, light);
  // Only the used vertices, each once: the two top triangles' 4 corners; 2j mesh, 2j + 1 extruded.
  const auto k = static_cast<std::uint32_t>(b.vol.source.size());
  EXPECT_EQ(k, 4u);
  ASSERT_EQ(b.vol.vertices.size(), 2u * k);
  EXPECT_EQ(std::set<std::uint32_t>(b.vol.source.begin(), b.vol.source.end()), used_mesh_vertices(b.vol));
  EXPECT_EQ(used_mesh_vertices(b.vol).size(), std::size_t{k});
  for (std::uint32_t j = 0; j < k; ++j) {
    const Vec3<T>& p = m.positions[b.vol.source[j]];
    EXPECT_EQ(b.vol.vertices[2 * j], Vec4<T>(p.x(), p.y(), p.z(), 1));
    EXPECT_EQ(b.vol.vertices[2 * j + 1], extrude_to_infinity(b.vol.vertices[2 * j], light));
  }
  const VolumeRanges& r = b.vol.ranges;
  EXPECT_EQ(r.side_first, 0u);
  EXPECT_EQ(r.side_count, 4u * 6u);  // 4 silhouette edges, 2 triangles each
  EXPECT_EQ(r.light_cap_first, r.side_count);
  EXPECT_EQ(r.light_cap_count, 2u * 3u);
  EXPECT_EQ(r.dark_cap_first, r.light_cap_first + r.light_cap_count);
  EXPECT_EQ(r.dark_cap_count, 2u * 3u);
  EXPECT_EQ(b.vol.indices.size(), std::size_t{r.side_count + r.light_cap_count + r.dark_cap_count});
  // Side quad of silhouette edge (from, to): (from, to, to'), (from, to', from'); the first edge
  // names the first two vertices.
  const SilhouetteEdge e = b.sil.edges[0];
  EXPECT_EQ(b.vol.source[0], e.from);
  EXPECT_EQ(b.vol.source[1], e.to);
  EXPECT_EQ((std::vector<std::uint32_t>(b.vol.indices.begin(), b.vol.indices.begin() + 6)),
            (std::vector<std::uint32_t>{0, 2, 3, 0, 3, 1}));
  // Dark cap: the light cap's triangles, extruded and walked backwards.
  for (std::uint32_t i = 0; i < r.light_cap_count; i += 3) {
    const std::uint32_t* lc = &b.vol.indices[r.light_cap_first + i];
    const std::uint32_t* dc = &b.vol.indices[r.dark_cap_first + i];
    EXPECT_EQ(dc[0], lc[0] + 1);
    EXPECT_EQ(dc[1], lc[2] + 1);
    EXPECT_EQ(dc[2], lc[1] + 1);
  }
  EXPECT_TRUE(closed_and_consistent(b.vol.indices));
}

TYPED_TEST(VolumeTest, CappedVolumesAreClosedForEveryKindOfLightAndMesh) {
  using T = TypeParam;
  const std::vector<TriangleMesh<T>> meshes{test::cube<T>(), test::open_box<T>(), test::cube_with_fin<T>(),
                                            test::miswound_cube<T>(), make_uv_sphere(T(1), 16, 9).value(),
                                            make_torus(T(2), T(0.5), 24, 12).value()};
  const std::vector<Vec4<T>> lights{Vec4<T>(T(0.2), 10, T(0.1), 1), Vec4<T>(10, 10, T(0.3), 1), Vec4<T>(T(0.3), T(0.2), 10, 1),
                                    Vec4<T>(1, 2, -3, 0)};
  for (const auto& m : meshes)
    for (const auto& l : lights)
      for (const bool finite : {false, true}) {
        VolumeOptions<T> opt;
        if (finite) opt.finite_distance = T(20);
        const auto b = build(m, l, opt);
        EXPECT_TRUE(closed_and_consistent(b.vol.indices)) << "light " << l.transpose() << (finite ? " finite" : " infinite");
      }
}

TYPED_TEST(VolumeTest, DirectionalToInfinityHasOneApexAndNoDarkCap) {
  using T = TypeParam;
  const auto m = make_uv_sphere(T(1), 16, 9).value();
  const Vec4<T> light(1, 2, -3, 0);
  const auto b = build(m, light);  // dark_cap requested (the default): not needed, not emitted
  const auto k = static_cast<std::uint32_t>(b.vol.source.size());
  ASSERT_EQ(b.vol.vertices.size(), k + 1u);
  EXPECT_EQ(b.vol.vertices[k], Vec4<T>(-1, -2, 3, 0));
  for (std::uint32_t j = 0; j < k; ++j) {
    const Vec3<T>& p = m.positions[b.vol.source[j]];
    EXPECT_EQ(b.vol.vertices[j], Vec4<T>(p.x(), p.y(), p.z(), 1));
  }
  EXPECT_EQ(b.vol.ranges.side_count, 3u * b.sil.edges.size());
  EXPECT_EQ(b.vol.ranges.dark_cap_count, 0u);
  for (std::uint32_t i = 0; i < b.vol.ranges.side_count; i += 3) EXPECT_EQ(b.vol.indices[i + 2], k);
  EXPECT_TRUE(closed_and_consistent(b.vol.indices));
}

TYPED_TEST(VolumeTest, ZPassOptionsGiveSidesOnly) {
  using T = TypeParam;
  VolumeOptions<T> opt;
  opt.light_cap = opt.dark_cap = false;
  const auto b = build(make_torus(T(2), T(0.5), 24, 12).value(), Vec4<T>(1, 5, 2, 1), opt);
  EXPECT_EQ(b.vol.indices.size(), 6u * b.sil.edges.size());
  EXPECT_EQ(b.vol.ranges.light_cap_count + b.vol.ranges.dark_cap_count, 0u);
  // Only the silhouette's vertices and their extrusions are in the buffer.
  std::set<std::uint32_t> silhouette_vertices;
  for (const SilhouetteEdge& e : b.sil.edges) silhouette_vertices.insert({e.from, e.to});
  EXPECT_EQ(std::set<std::uint32_t>(b.vol.source.begin(), b.vol.source.end()), silhouette_vertices);
  EXPECT_EQ(b.vol.source.size(), silhouette_vertices.size());
  EXPECT_EQ(b.vol.vertices.size(), 2 * silhouette_vertices.size());
}

TYPED_TEST(VolumeTest, FiniteExtrusionMovesEachVertexByTheDistanceAwayFromTheLight) {
  using T = TypeParam;
  const auto m = make_uv_sphere(T(1), 12, 7).value();
  const Vec4<T> light(1, 4, 2, 1);
  VolumeOptions<T> opt;
  opt.finite_distance = T(7);
  const auto b = build(m, light, opt);
  const std::size_t k = b.vol.source.size();
  ASSERT_EQ(b.vol.vertices.size(), 2 * k);
  EXPECT_EQ(used_mesh_vertices(b.vol).size(), k);
  for (std::size_t j = 0; j < k; ++j) {
    const Vec3<T>& p = m.positions[b.vol.source[j]];
    EXPECT_EQ(b.vol.vertices[2 * j], Vec4<T>(p.x(), p.y(), p.z(), 1));
    const Vec4<T>& e = b.vol.vertices[2 * j + 1];
    EXPECT_EQ(e.w(), T(1));
    const Vec3<T> moved = e.template head<3>() - p;
    const Vec3<T> away = p - light.template head<3>();
    // Norm, division, product and sum over values up to ~12: a few ulps of that scale.
    EXPECT_CLOSE(moved.norm(), T(7), eps<T>(16, T(12)));
    EXPECT_CLOSE(moved.normalized().dot(away.normalized()), T(1), eps<T>(16));
  }
}

TYPED_TEST(VolumeTest, LightOnACasterVertexIsReported) {
  using T = TypeParam;
  const auto caster = make_shadow_caster(test::cube<T>()).value();
  Silhouette<T> s;
  ShadowVolume<T> v;
  ASSERT_TRUE(find_silhouette(caster, Vec4<T>(1, 1, 1, 1), s).ok());  // vertex 7
  EXPECT_EQ(build_shadow_volume(caster, s, VolumeOptions<T>{}, v).error(), Error::LightOnCaster);
  VolumeOptions<T> finite;
  finite.finite_distance = T(3);
  EXPECT_EQ(build_shadow_volume(caster, s, finite, v).error(), Error::LightOnCaster);
}

TYPED_TEST(VolumeTest, BadFiniteDistanceIsRefused) {
  using T = TypeParam;
  const auto caster = make_shadow_caster(test::cube<T>()).value();
  Silhouette<T> s;
  ShadowVolume<T> v;
  ASSERT_TRUE(find_silhouette(caster, Vec4<T>(0, 5, 0, 1), s).ok());
  VolumeOptions<T> opt;
  opt.finite_distance = T(0);
  EXPECT_EQ(build_shadow_volume(caster, s, opt, v).error(), Error::DistanceNotPositive);
  opt.finite_distance = std::numeric_limits<T>::infinity();
  EXPECT_EQ(build_shadow_volume(caster, s, opt, v).error(), Error::NonFinite);
}

// One ShadowVolume for casters of different sizes, capped and not, one after the other (as a
// renderer does): the same buffers as a fresh one each time (the scratch numbering is reset).
TYPED_TEST(VolumeTest, OneVolumeForManyCastersEqualsFreshOnes) {
  using T = TypeParam;
  const std::vector<TriangleMesh<T>> meshes{make_uv_sphere(T(1), 24, 13).value(), test::cube<T>(), test::cube_with_fin<T>(),
                                            make_torus(T(2), T(0.5), 24, 12).value()};
  ShadowVolume<T> reused;
  for (int round = 0; round < 2; ++round)
    for (const auto& m : meshes)
      for (const bool caps : {true, false}) {
        VolumeOptions<T> opt;
        opt.light_cap = opt.dark_cap = caps;
        const auto b = build(m, Vec4<T>(3, 4, 5, 1), opt);
        ASSERT_TRUE(build_shadow_volume(b.caster, b.sil, opt, reused).ok());
        EXPECT_EQ(reused.indices, b.vol.indices);
        EXPECT_EQ(reused.source, b.vol.source);
        EXPECT_EQ(reused.vertices, b.vol.vertices);
      }
  EXPECT_EQ(std::count(reused.volume_vertex.begin(), reused.volume_vertex.end(), kNoVolumeVertex),
            static_cast<std::ptrdiff_t>(reused.volume_vertex.size()));
}

TYPED_TEST(VolumeTest, BuffersAreReused) {
  using T = TypeParam;
  const auto caster = make_shadow_caster(make_uv_sphere(T(1), 24, 13).value()).value();
  Silhouette<T> s;
  ShadowVolume<T> v;
  ASSERT_TRUE(find_silhouette(caster, Vec4<T>(3, 4, 5, 1), s).ok());
  ASSERT_TRUE(build_shadow_volume(caster, s, VolumeOptions<T>{}, v).ok());
  v.indices.reserve(2 * v.indices.size());
  const auto* vp = v.vertices.data();
  v.source.reserve(2 * v.source.size());
  const auto* ip = v.indices.data();
  const auto* sp = v.source.data();
  ASSERT_TRUE(find_silhouette(caster, Vec4<T>(-3, 2, 1, 1), s).ok());
  ASSERT_TRUE(build_shadow_volume(caster, s, VolumeOptions<T>{}, v).ok());
  EXPECT_EQ(v.vertices.data(), vp);
  EXPECT_EQ(v.indices.data(), ip);
  EXPECT_EQ(v.source.data(), sp);
}

}  // namespace
}  // namespace shadowref
