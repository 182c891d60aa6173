// shapes_test.cpp — each shape of the scene format through the loader: closed where it should be,
// wound outward (positive signed volume equal to the analytic one where it is exact), and placed
// where the transform says.
#include <gtest/gtest.h>

#include <map>
#include <numbers>
#include <utility>

#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/shapes.hpp"
#include "test_scene_json.hpp"

namespace shadowref::scene {
namespace {

using nlohmann::json;

// Σ over triangles of v0 · (v1 × v2) / 6: the enclosed volume, positive when wound outward.
template <class T>
double signed_volume(const TriangleMesh<T>& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    const Vec3<double> a = m.positions[t[0]].template cast<double>(), b = m.positions[t[1]].template cast<double>(),
                       c = m.positions[t[2]].template cast<double>();
    v += a.dot(b.cross(c)) / 6;
  }
  return v;
}

// True when every directed edge appears once and its reverse once: closed, consistently wound.
template <class T>
bool closed_and_consistent(const TriangleMesh<T>& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
  for (const auto& [e, count] : edges) {
    if (count != 1) return false;
    const auto rev = edges.find({e.second, e.first});
    if (rev == edges.end() || rev->second != 1) return false;
  }
  return true;
}

Object load_one_shape(const json& shape, const json& transform = nullptr) {
  json doc = test::minimal_scene();
  doc["objects"][1]["shape"] = shape;
  if (transform.is_null()) doc["objects"][1].erase("transform");
  else doc["objects"][1]["transform"] = transform;
  return parse_scene(doc.dump(), std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / "t.json").objects[1];
}

// Volumes below are compared in float-rounded positions: 1e-5 relative covers float rounding of
// each vertex (6e-8 relative) summed over the few hundred triangles involved.
constexpr double kVolumeTolerance = 1e-5;

TEST(Shapes, Box) {
  const Object o = load_one_shape({{"type", "box"}, {"size", {1, 2, 3}}});
  EXPECT_EQ(o.mesh.triangles.size(), 12u);
  EXPECT_TRUE(closed_and_consistent(o.mesh));
  EXPECT_NEAR(signed_volume(o.mesh), 6.0, 6.0 * kVolumeTolerance);
}

TEST(Shapes, SphereIsClosedAndOutward) {
  const Object o = load_one_shape({{"type", "sphere"}, {"radius", 2}, {"segments", 24}, {"rings", 12}});
  EXPECT_EQ(o.mesh.triangles.size(), 2u * 24 * 11);
  EXPECT_TRUE(closed_and_consistent(o.mesh));
  // The inscribed polyhedron is smaller than the sphere but within 5 % at this tessellation.
  const double sphere = 4.0 / 3.0 * std::numbers::pi * 8;
  EXPECT_GT(signed_volume(o.mesh), 0.95 * sphere);
  EXPECT_LT(signed_volume(o.mesh), sphere);
}

TEST(Shapes, SphereDefaults) {
  const Object o = load_one_shape({{"type", "sphere"}, {"radius", 1}});
  EXPECT_EQ(o.mesh.triangles.size(), 2u * 32 * 15);  // segments 32, rings 16
}

TEST(Shapes, TorusIsClosedAndOutward) {
  const Object o = load_one_shape({{"type", "torus"}, {"major_radius", 2}, {"minor_radius", 0.5}, {"segments", 32}, {"sides", 16}});
  EXPECT_EQ(o.mesh.triangles.size(), 2u * 32 * 16);
  EXPECT_TRUE(closed_and_consistent(o.mesh));
  const double torus = 2 * std::numbers::pi * std::numbers::pi * 2 * 0.25;
  EXPECT_GT(signed_volume(o.mesh), 0.95 * torus);
  EXPECT_LT(signed_volume(o.mesh), torus);
}

TEST(Shapes, PlaneFacesUp) {
  const Object o = load_one_shape({{"type", "plane"}, {"size", {4, 2}}});
  ASSERT_EQ(o.mesh.triangles.size(), 2u);
  for (const auto& t : o.mesh.triangles) {
    const Vec3<float> n = (o.mesh.positions[t[1]] - o.mesh.positions[t[0]]).cross(o.mesh.positions[t[2]] - o.mesh.positions[t[0]]);
    EXPECT_GT(n.y(), 0.0f);
  }
  EXPECT_FLOAT_EQ(o.mesh.positions[0].cwiseAbs().x(), 2.0f);
  EXPECT_FLOAT_EQ(o.mesh.positions[0].cwiseAbs().z(), 1.0f);
}

TEST(Shapes, StairsVolumeAndClosure) {
  for (int steps : {1, 2, 5, 12}) {
    const TriangleMesh<double> m = make_stairs(steps, Vec3<double>(2, 3, 4));
    EXPECT_TRUE(closed_and_consistent(m)) << steps << " steps";
    // Step i has height H (i+1)/n over depth D/n: volume W D H (n+1) / (2n).
    const double expected = 2.0 * 4.0 * 3.0 * (steps + 1) / (2.0 * steps);
    EXPECT_NEAR(signed_volume(m), expected, 1e-12 * expected) << steps << " steps";  // double: exact up to rounding
  }
}

TEST(Shapes, StairsRiseTowardPlusZ) {
  const TriangleMesh<double> m = make_stairs(4, Vec3<double>(1, 2, 4));
  double top_z = -1e9;
  for (const auto& p : m.positions)
    if (p.y() == 2.0) top_z = std::max(top_z, p.z());
  EXPECT_EQ(top_z, 2.0);
  for (const auto& p : m.positions) {
    EXPECT_GE(p.y(), 0.0);
    EXPECT_LE(std::abs(p.z()), 2.0);
  }
}

TEST(Transforms, ScaleThenRotateThenTranslate) {
  // The box vertex (+0.5, +0.5, +0.5) of a unit box: scale 2 → (1, 1, 1); rotate 90° about +z
  // → (−1, 1, 1); translate (10, 0, 0) → (9, 1, 1). Any other order lands elsewhere.
  const Object o = load_one_shape({{"type", "box"}, {"size", {1, 1, 1}}},
                                  {{"scale", 2}, {"rotate", {{"axis", {0, 0, 1}}, {"degrees", 90}}}, {"translate", {10, 0, 0}}});
  bool found = false;
  for (const auto& p : o.mesh.positions) found = found || (p - Vec3<float>(9, 1, 1)).norm() < 1e-5f;  // float rotation rounding
  EXPECT_TRUE(found);
  EXPECT_NEAR(signed_volume(o.mesh), 8.0, 8.0 * kVolumeTolerance);
}

TEST(Transforms, MirrorKeepsOutwardWinding) {
  const Object o = load_one_shape({{"type", "box"}, {"size", {1, 2, 3}}}, {{"scale", {-1, 1, 1}}});
  EXPECT_GT(signed_volume(o.mesh), 0.0) << "a mirroring transform must flip the winding back";
  EXPECT_TRUE(closed_and_consistent(o.mesh));
}

TEST(Transforms, NonUniformScale) {
  const Object o = load_one_shape({{"type", "box"}, {"size", {1, 1, 1}}}, {{"scale", {1, 2, 3}}});
  EXPECT_NEAR(signed_volume(o.mesh), 6.0, 6.0 * kVolumeTolerance);
}

}  // namespace
}  // namespace shadowref::scene
