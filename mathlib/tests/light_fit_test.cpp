// light_fit_test.cpp — the shadow-map views of light_fit.hpp hold every vertex of the scene, in
// every run convention, and the helpers they are built from do what they say.
#include <gtest/gtest.h>

#include <random>

#include "shadowref/light_fit.hpp"
#include "shadowref/primitives.hpp"

namespace shadowref {
namespace {

// A ground plate and a box over it: the geometry of most catalogue scenes.
struct Geometry {
  TriangleMesh<float> ground = make_plane<float>(5.0f, 5.0f).value();
  TriangleMesh<float> box = make_box<float>(Vec3<float>(-0.5f, 0.0f, -0.5f), Vec3<float>(0.5f, 1.0f, 0.5f)).value();
  std::vector<const TriangleMesh<float>*> meshes{&ground, &box};
};

// Window depth in [0, 1] of a clip-space point (any convention: −1..1 is mapped, 0..1 kept).
double window_depth(const RunConvention& c, const Vec4<double>& h) {
  const double z = h.z() / h.w();
  return c.clip.depth == DepthRange::NegOneToOne ? 0.5 * z + 0.5 : z;
}

// Every vertex of every mesh falls inside `view` (x, y in [−1, 1], depth in [0, 1], w > 0), with
// a relative slack for the double rounding of the matrices (1e-9 of the unit square).
void expect_holds_all(const RunConvention& c, const LightView& view, const Geometry& g) {
  const Mat4<double> m = view.projection * view.view;
  for (const TriangleMesh<float>* mesh : g.meshes)
    for (const Vec3<float>& p : mesh->positions) {
      const Vec4<double> h = m * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
      ASSERT_GT(h.w(), 0.0) << c.name;
      EXPECT_LE(std::abs(h.x() / h.w()), 1.0 + 1e-9) << c.name;
      EXPECT_LE(std::abs(h.y() / h.w()), 1.0 + 1e-9) << c.name;
      const double d = window_depth(c, h);
      EXPECT_GE(d, -1e-9) << c.name;
      EXPECT_LE(d, 1.0 + 1e-9) << c.name;
    }
}

TEST(LightFit, DirectionalLightHoldsTheWholeSceneInOneOrthographicView) {
  const Geometry g;
  for (const RunConvention& c : kRunConventions) {
    const LightFit fit = fit_light(c, Vec4<double>(0.3, 1.0, 0.2, 0.0), g.meshes).value();
    ASSERT_EQ(fit.views.size(), 1u);
    EXPECT_FALSE(fit.cube);
    EXPECT_EQ(fit.size, kDirectionalAutoSize);
    EXPECT_EQ(fit.views[0].projection(3, 3), 1.0) << "orthographic";
    expect_holds_all(c, fit.views[0], g);
  }
}

TEST(LightFit, PointLightOutsideTheBoundsGetsOnePerspectiveViewHoldingEverything) {
  const Geometry g;
  for (const RunConvention& c : kRunConventions) {
    const LightFit fit = fit_light(c, Vec4<double>(2.0, 6.0, 1.0, 1.0), g.meshes).value();
    ASSERT_EQ(fit.views.size(), 1u);
    EXPECT_FALSE(fit.cube);
    expect_holds_all(c, fit.views[0], g);
  }
}

TEST(LightFit, PointLightInsideTheBoundsGetsACubeWhoseFacesHoldEveryVertex) {
  const Geometry g;
  const Vec3<double> pos(0.0, 2.0, 0.0);  // inside the box of the 10 × 10 ground and the unit box
  for (const RunConvention& c : kRunConventions) {
    const LightFit fit = fit_light(c, Vec4<double>(pos.x(), pos.y(), pos.z(), 1.0), g.meshes).value();
    ASSERT_TRUE(fit.cube);
    ASSERT_EQ(fit.views.size(), 6u);
    EXPECT_FALSE(fit.views[3].empty) << "−y looks at the ground";
    EXPECT_TRUE(fit.views[2].empty) << "+y sees nothing: every mesh lies below the light";
    // Each vertex, in the face a cube-map lookup picks (largest component of p − light), lies inside
    // that face's frustum.
    const Vec3<double> axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const TriangleMesh<float>* mesh : g.meshes)
      for (const Vec3<float>& pf : mesh->positions) {
        const Vec3<double> d = pf.cast<double>() - pos;
        int face = 0;
        for (int k = 1; k < 6; ++k)
          if (d.dot(axes[k]) > d.dot(axes[face])) face = k;
        const LightView& v = fit.views[static_cast<std::size_t>(face)];
        ASSERT_FALSE(v.empty);
        const Vec4<double> h = v.projection * v.view * Vec4<double>(pf.x(), pf.y(), pf.z(), 1.0);
        ASSERT_GT(h.w(), 0.0);
        EXPECT_LE(std::abs(h.x() / h.w()), 1.0 + 1e-9) << c.name << " face " << face;
        EXPECT_LE(std::abs(h.y() / h.w()), 1.0 + 1e-9) << c.name << " face " << face;
        const double depth = window_depth(c, h);
        EXPECT_GE(depth, -1e-9) << c.name;
        EXPECT_LE(depth, 1.0 + 1e-9) << c.name;
      }
  }
}

TEST(LightFit, EveryConventionSeesTheSameTexelForTheSamePoint) {
  // The light's x, y (hence which texel a point reads) do not depend on the convention: the d3d
  // world mirror and its left-handed look-at cancel, as the camera's do.
  const Geometry g;
  const Vec4<double> L(2.0, 6.0, 1.0, 1.0);
  const LightFit gl = fit_light(kDefaultConvention, L, g.meshes).value();
  for (const RunConvention& c : kRunConventions) {
    const LightFit fit = fit_light(c, L, g.meshes).value();
    const Mat4<double> a = gl.views[0].projection * gl.views[0].view, b = fit.views[0].projection * fit.views[0].view;
    for (const Vec3<float>& p : g.box.positions) {
      const Vec4<double> ha = a * Vec4<double>(p.x(), p.y(), p.z(), 1.0), hb = b * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
      EXPECT_NEAR(ha.x() / ha.w(), hb.x() / hb.w(), 1e-12) << c.name;
      EXPECT_NEAR(ha.y() / ha.w(), hb.y() / hb.w(), 1e-12) << c.name;
    }
  }
}

TEST(LightFit, MapSizeIsTheCallersOrAutomaticWithinItsClamp) {
  const Geometry g;
  const Vec4<double> L(2.0, 6.0, 1.0, 1.0);
  LightFitOptions o;
  o.map_size = 512;
  EXPECT_EQ(fit_light(kDefaultConvention, L, g.meshes, o).value().size, 512);
  o.map_size = 0;
  o.camera_tan_per_pixel = 1.0;  // huge camera pixels: the floor
  EXPECT_EQ(fit_light(kDefaultConvention, L, g.meshes, o).value().size, kAutoMinSize);
  o.camera_tan_per_pixel = 1e-7;  // tiny camera pixels: the ceiling
  EXPECT_EQ(fit_light(kDefaultConvention, L, g.meshes, o).value().size, kAutoMaxSize);
  EXPECT_EQ(fit_light(kDefaultConvention, Vec4<double>(0, 2, 0, 1), g.meshes, o).value().size, kCubeAutoMaxSize);
}

TEST(LightFit, RefusesEmptyAndNonFiniteInput) {
  const Geometry g;
  EXPECT_FALSE(fit_light(kDefaultConvention, Vec4<double>(0, 1, 0, 0), std::vector<const TriangleMesh<float>*>{}).ok());
  EXPECT_FALSE(fit_light(kDefaultConvention, Vec4<double>(std::nan(""), 1, 0, 1), g.meshes).ok());
}

TEST(ClosestPointOnTriangle, MatchesDenseSamplingInEveryRegion) {
  const Vec3<double> a(0, 0, 0), b(2, 0, 0), c(0, 1, 0.5);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 3.0);
  for (int i = 0; i < 200; ++i) {
    const Vec3<double> p(u(rng), u(rng), u(rng));
    const double got = (closest_point_on_triangle(p, a, b, c) - p).norm();
    double best = std::numeric_limits<double>::infinity();
    constexpr int kSteps = 200;  // a grid 1/200 of the edges apart: within 0.02 of the true closest point
    for (int s = 0; s <= kSteps; ++s)
      for (int t = 0; s + t <= kSteps; ++t) {
        const Vec3<double> q = a + (b - a) * (double(s) / kSteps) + (c - a) * (double(t) / kSteps);
        best = std::min(best, (q - p).norm());
      }
    EXPECT_LE(got, best + 1e-12) << "the closest point is at least as close as any sample";
    EXPECT_GE(got, best - 0.02) << "and no closer than the grid's resolution allows";
  }
}

TEST(LeastAlignedAxis, IsNeverParallelToTheDirection) {
  for (const Vec3<double>& d : {Vec3<double>(0, 1, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 0, -1), Vec3<double>(1, 1, 1)})
    EXPECT_GT(d.normalized().cross(least_aligned_axis(d)).norm(), 0.5);
}

}  // namespace
}  // namespace shadowref
