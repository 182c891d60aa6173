// visibility_test.cpp — hand cases of the reference's visibility rule (shadow_ray.hpp), where the
// answer follows from elementary geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/reference/shadow_ray.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::reference {
namespace {

// A unit sphere centred at (0, 2, 0) over the ground y = 0; the light 3 above the centre.
// The shadow is a disc: the cone from the light tangent to the sphere has sin(a) = 1/3, so on the
// ground (5 below the light) its radius is 5 tan(a) = 5 / sqrt(8) ≈ 1.768. The sphere is a
// 64 × 32 polyhedron inscribed in the sphere, whose silhouette lies within 0.5 % of the radius:
// test points stay 0.07 or more from that edge.
scene::Scene sphere_scene(const std::string& light) {
  return scene::parse_scene(R"({"name": "t", "camera": {"position": [0, 4, 8], "target": [0, 0, 0]},
    "lights": [)" + light + R"(],
    "objects": [{"shape": {"type": "plane", "size": [20, 20]}, "receiver": true},
                {"shape": {"type": "sphere", "radius": 1, "segments": 64}, "transform": {"translate": [0, 2, 0]}}]})",
                            "hand.json");
}

const Vec3<double> kUp(0, 1, 0);

TEST(Visibility, BelowTheSphereCentreIsShadowed) {
  const scene::Scene s = sphere_scene(R"({"type": "point", "position": [0, 5, 0]})");
  const EmbreeScene e(s);
  EXPECT_EQ(lit_fraction(e, Vec3<double>(0, 0, 0), kUp, s.lights[0]), 0.0);
}

TEST(Visibility, InsideAndOutsideTheShadowCone) {
  const scene::Scene s = sphere_scene(R"({"type": "point", "position": [0, 5, 0]})");
  const EmbreeScene e(s);
  const double r = 5 / std::sqrt(8.0);
  EXPECT_EQ(lit_fraction(e, Vec3<double>(r - 0.1, 0, 0), kUp, s.lights[0]), 0.0) << "just inside the cone";
  EXPECT_EQ(lit_fraction(e, Vec3<double>(0, 0, r + 0.07), kUp, s.lights[0]), 1.0) << "just outside the cone";
  EXPECT_EQ(lit_fraction(e, Vec3<double>(5, 0, 5), kUp, s.lights[0]), 1.0) << "far outside";
}

TEST(Visibility, DirectionalShadowIsACylinder) {
  // w = 0: the shadow of the unit sphere is the disc of radius 1 under it, whatever the height.
  const scene::Scene s = sphere_scene(R"({"type": "directional", "direction": [0, 1, 0]})");
  const EmbreeScene e(s);
  EXPECT_EQ(lit_fraction(e, Vec3<double>(0.9, 0, 0), kUp, s.lights[0]), 0.0);
  EXPECT_EQ(lit_fraction(e, Vec3<double>(1.1, 0, 0), kUp, s.lights[0]), 1.0);
}

TEST(Visibility, FacingAwayIsAttachedShadow) {
  // The sphere's south pole region faces the ground, away from the light: shadowed by itself,
  // without any ray (rule 1), and the top faces the light and is lit.
  const scene::Scene s = sphere_scene(R"({"type": "point", "position": [0, 5, 0]})");
  const EmbreeScene e(s);
  EXPECT_EQ(lit_fraction(e, Vec3<double>(0, 1, 0), -kUp, s.lights[0]), 0.0);
  RTCRay ray{};
  EXPECT_EQ(make_shadow_ray(Vec3<double>(0, 1, 0), -kUp, Vec4<double>(0, 5, 0, 1), e.epsilon(), ray), ShadowRayKind::Attached);
  EXPECT_EQ(lit_fraction(e, Vec3<double>(0, 3, 0), kUp, s.lights[0]), 1.0);
}

TEST(Visibility, RectLightPenumbraIsFractional) {
  // A 2 × 2 area light centred 3 above the sphere: under the centre every sample is blocked
  // (each sample's shadow disc still covers the origin: the samples are within 1.41 of the axis
  // and the discs' radius exceeds 1.5); at the edge of the point light's shadow only some are.
  const scene::Scene s = sphere_scene(R"({"type": "rect", "corner": [-1, 5, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "samples": 8})");
  const EmbreeScene e(s);
  EXPECT_EQ(lit_fraction(e, Vec3<double>(0, 0, 0), kUp, s.lights[0]), 0.0);
  const double f = lit_fraction(e, Vec3<double>(5 / std::sqrt(8.0), 0, 0), kUp, s.lights[0]);
  EXPECT_GT(f, 0.0);
  EXPECT_LT(f, 1.0);
}

TEST(Visibility, LightSamplesAreTheGridCentres) {
  scene::Light l;
  l.type = scene::LightType::Rect;
  l.corner = Vec3<double>(0, 0, 0);
  l.edge_u = Vec3<double>(4, 0, 0);
  l.edge_v = Vec3<double>(0, 0, 2);
  l.samples = 2;
  const auto s = light_samples(l);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0], Vec4<double>(1, 0, 0.5, 1));
  EXPECT_EQ(s[3], Vec4<double>(3, 0, 1.5, 1));
}

}  // namespace
}  // namespace shadowref::reference
