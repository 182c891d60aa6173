// Unit tests of shadowref/volume_strategy.hpp: the near rectangle from a projection, and the
// z-pass / z-fail choice for a light in front of, behind and in the near plane, and directional —
// each verdict checked against the lit-face oracle on the near rectangle itself.
#include "shadowref/volume_strategy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scalar_types.hpp"
#include "shadowref/primitives.hpp"
#include "shadowref/projection.hpp"
#include "test_meshes.hpp"

namespace shadowref {
namespace {

using test::eps;

template <class T>
class VolumeStrategyTest : public ::testing::Test {};
TYPED_TEST_SUITE(VolumeStrategyTest, test::FloatAndDouble);

// The camera of every case: at the origin, looking down -z (view = identity), 90 degrees, near 1:
// the near rectangle is [-1, 1]^2 at z = -1.
template <class T>
std::array<Vec3<T>, 4> camera_near() {
  const auto p = perspective_infinite<T>(std::numbers::pi_v<T> / T(2), T(1), T(1));
  return near_rectangle(p.value()).value();
}

// The largest count of lit faces between a point of the near rectangle (a 9x9 grid, shifted off
// the rectangle's centre lines so that no sample ray runs exactly along the test spheres' edges)
// and the light.
template <class T>
int near_rectangle_shadow(const TriangleMesh<T>& m, const Vec4<T>& light, const std::array<Vec3<T>, 4>& c) {
  int worst = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) {
      const T u = (T(i) + T(0.3)) / T(9), v = (T(j) + T(0.4)) / T(9);
      const Vec3<T> q = (c[0] * (1 - u) + c[1] * u) * (1 - v) + (c[3] * (1 - u) + c[2] * u) * v;
      worst = std::max(worst, test::lit_faces_toward_light(m, light, q));
    }
  return worst;
}

// A sphere mesh around c, nudged by a small irregular offset: the oracle's strict ray-triangle
// test misses rays that run exactly along a mesh edge, and the cases' axis-aligned set-ups would
// otherwise aim sample rays right at the sphere's pole and seam edges.
template <class T>
TriangleMesh<T> sphere_at(const Vec3<T>& c, T r) {
  auto m = make_uv_sphere(r, 15, 9).value();
  const Vec3<T> nudge(T(0.0123), T(0.0311), T(-0.0217));
  for (auto& p : m.positions) p += c + nudge;
  return m;
}

TYPED_TEST(VolumeStrategyTest, NearRectangleOfAPerspective) {
  using T = TypeParam;
  const auto c = camera_near<T>();
  const T xs[4] = {-1, 1, 1, -1}, ys[4] = {-1, -1, 1, 1};
  // Inverse of a matrix with entries ~1 and one division: a few ulps.
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(test::near_matrix(c[i], Vec3<T>(xs[i], ys[i], -1), eps<T>(8)));
  // Direct3D convention (left-handed, 0..1): the near plane is at z = +1 (view looks down +z).
  const auto d3d = perspective<T>(std::numbers::pi_v<T> / T(2), T(1), T(1), T(100), kDirect3D).value();
  const auto c2 = near_rectangle(d3d, kDirect3D).value();
  for (int i = 0; i < 4; ++i) EXPECT_CLOSE(c2[i].z(), T(1), eps<T>(8));
  EXPECT_EQ(near_rectangle(Mat4<T>(Mat4<T>::Zero())).error(), Error::SingularMatrix);
}

struct Case {
  const char* what;
  double light[4];
  double center[3];
  double radius;
  StencilMethod expected;
};

TYPED_TEST(VolumeStrategyTest, LightInFrontBehindAndInTheNearPlane) {
  using T = TypeParam;
  const Case cases[] = {
      // Light in front of the near plane (down -z).
      {"front: caster between near plane and light", {0, 0, -10, 1}, {0, 0, -5}, 1, StencilMethod::ZFail},
      {"front: caster off to the side", {0, 0, -10, 1}, {20, 0, -5}, 1, StencilMethod::ZPass},
      {"front: caster beyond the light", {0, 0, -10, 1}, {0, 0, -20}, 1, StencilMethod::ZPass},
      // Light behind the camera (+z): the clip volume reaches backward past the eye.
      {"behind: caster between light and camera", {0, 0, 10, 1}, {0, 0, 5}, 1, StencilMethod::ZFail},
      {"behind: caster in front of the camera", {0, 0, 10, 1}, {0, 0, -5}, 1, StencilMethod::ZPass},
      // Light in the near plane: the clip volume is flat, the near rectangle and the light.
      {"in plane: caster cuts the plane between rectangle and light", {5, 0, -1, 1}, {3, 0, -1}, 0.5, StencilMethod::ZFail},
      {"in plane: caster behind the plane", {5, 0, -1, 1}, {3, 0, -3}, 0.5, StencilMethod::ZPass},
      // Directional: the near rectangle swept toward the light, to infinity.
      {"directional: caster above the camera", {0, 1, 0, 0}, {0, 5, -1}, 0.5, StencilMethod::ZFail},
      {"directional: caster below the camera", {0, 1, 0, 0}, {0, -5, -1}, 0.5, StencilMethod::ZPass},
  };
  const auto near = camera_near<T>();
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const Vec4<T> light(T(c.light[0]), T(c.light[1]), T(c.light[2]), T(c.light[3]));
    const TriangleMesh<T> caster = sphere_at(Vec3<T>(T(c.center[0]), T(c.center[1]), T(c.center[2])), T(c.radius));
    const auto sphere = bounding_sphere(caster);
    ASSERT_TRUE(sphere.ok());
    const auto method = choose_stencil_method(near, light, *sphere);
    ASSERT_TRUE(method.ok()) << method.message();
    EXPECT_EQ(*method, c.expected) << to_string(*method);
    // The verdict against the oracle: z-pass only where no point of the near rectangle is shadowed;
    // and these z-fail cases were built so that some point is.
    const int shadow = near_rectangle_shadow(caster, light, near);
    if (*method == StencilMethod::ZPass) EXPECT_EQ(shadow, 0);
    else EXPECT_GT(shadow, 0);
  }
}

TYPED_TEST(VolumeStrategyTest, BoundingSphereContainsTheMesh) {
  using T = TypeParam;
  const auto m = test::cube<T>();
  const auto s = bounding_sphere(m).value();
  EXPECT_EQ(s.center, Vec3<T>(0, 0, 0));
  EXPECT_CLOSE(s.radius, std::sqrt(T(3)), eps<T>(2, T(2)));  // one sqrt of an exact 3
  EXPECT_EQ(bounding_sphere(TriangleMesh<T>{}).error(), Error::EmptyMesh);
}

TYPED_TEST(VolumeStrategyTest, BadInputIsRefused) {
  using T = TypeParam;
  const auto near = camera_near<T>();
  const BoundingSphere<T> s{Vec3<T>(0, 0, -5), T(1)};
  EXPECT_EQ(choose_stencil_method(near, Vec4<T>(0, 0, 0, 0), s).error(), Error::ZeroLight);
  EXPECT_EQ(choose_stencil_method(near, Vec4<T>(0, 0, -10, -1), s).error(), Error::NegativeLightW);
  EXPECT_EQ(choose_stencil_method(near, Vec4<T>(0, 0, -10, 1), BoundingSphere<T>{Vec3<T>(0, 0, -5), T(-1)}).error(),
            Error::NonFinite);
}

TYPED_TEST(VolumeStrategyTest, TouchingTheClipVolumeExactlyIsConservative) {
  using T = TypeParam;
  // A sphere tangent to the near plane's clip volume (light in front, sphere touching the plane
  // through the light and the rectangle's right edge from outside) counts as touching.
  const auto near = camera_near<T>();
  const Vec4<T> light(0, 0, -10, 1);
  // The plane through (1, ±1, -1) and (0, 0, -10) is 9x - z = 10, outward normal (9, 0, -1)/sqrt(82);
  // (0.5, 0, -5.5) lies on its face of the clip volume. A sphere centred at distance exactly r
  // from it, outside, touches (up to rounding, which must count as touching).
  const Vec3<T> n = Vec3<T>(9, 0, -1).normalized();
  const Vec3<T> on_plane(T(0.5), 0, T(-5.5));
  const BoundingSphere<T> touching{on_plane + n * T(2), T(2)};
  EXPECT_EQ(choose_stencil_method(near, light, touching).value(), StencilMethod::ZFail);
  const BoundingSphere<T> clear{on_plane + n * T(2.1), T(2)};
  EXPECT_EQ(choose_stencil_method(near, light, clear).value(), StencilMethod::ZPass);
}

}  // namespace
}  // namespace shadowref
