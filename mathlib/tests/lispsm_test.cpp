// lispsm_test.cpp — lispsm.hpp, held to what makes a warped map a directional light's map: in every
// convention, the points the camera sees of the scene land inside the map and its depth range; the
// light's rays stay parallel (a point and every point along the light from it share one map
// position, nearer the light nearer in depth); the warp spends texels near the camera (a texel
// there covers less of the ground than one far away, where the plain map's texels are all alike);
// a triangle keeps its winding; and a camera looking along the light gets the plain map.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "shadowref/lispsm.hpp"

namespace shadowref {
namespace {

// A sun_horizon-like layout: a 200 m ground box, a camera 2.5 m up looking along −z, a sun 17
// degrees up and to the side.
const std::array<Vec3<double>, 2> kBounds{Vec3<double>(-100, 0, -100), Vec3<double>(100, 12, 100)};
const Vec3<double> kTowardSun = Vec3<double>(-0.45, 0.3, 0.9).normalized();

CascadeCamera camera_looking(const Vec3<double>& forward) {
  CascadeCamera c;
  c.eye = Vec3<double>(0, 2.5, 10);
  c.forward = forward.normalized();
  c.fovy = 50 * std::acos(-1.0) / 180;
  c.aspect = 1;
  c.near = 0.1;
  return c;
}

Vec3<double> ndc(const LightView& v, const Vec3<double>& p, double* w = nullptr) {
  const Vec4<double> c = v.projection * v.view * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
  if (w) *w = c.w();
  return c.head<3>() / c.w();
}

// Points the camera sees of the scene: inside the box and inside the frustum's cone.
std::vector<Vec3<double>> seen_points(const CascadeCamera& camera, int count) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(kBounds[0].x(), kBounds[1].x()), y(kBounds[0].y(), kBounds[1].y()),
      z(kBounds[0].z(), kBounds[1].z());
  const double tan_half = std::tan(0.5 * camera.fovy);
  std::vector<Vec3<double>> out;
  while (static_cast<int>(out.size()) < count) {
    const Vec3<double> p(x(rng), y(rng), z(rng));
    const Vec3<double> d = p - camera.eye;
    const double along = d.dot(camera.forward);
    if (along > camera.near && (d - along * camera.forward).norm() <= along * tan_half) out.push_back(p);
  }
  return out;
}

TEST(Lispsm, WhatTheCameraSeesLiesInsideTheMapInEveryConvention) {
  const CascadeCamera camera = camera_looking(Vec3<double>(0, -0.03, -1));
  for (const RunConvention& c : kRunConventions) {
    const LightFit fit = fit_lispsm(c, kTowardSun, kBounds, camera, 1024).value();
    ASSERT_EQ(fit.views.size(), 1u);
    EXPECT_EQ(fit.size, 1024);
    const double lo = std::min(near_ndc_z(c), far_ndc_z(c)), hi = std::max(near_ndc_z(c), far_ndc_z(c));
    for (const Vec3<double>& p : seen_points(camera, 2000)) {
      double w = 0;
      const Vec3<double> q = ndc(fit.views[0], p, &w);
      ASSERT_GT(w, 0) << c.name;
      EXPECT_LE(std::abs(q.x()), 1 + 1e-9) << c.name;
      EXPECT_LE(std::abs(q.y()), 1 + 1e-9) << c.name;
      EXPECT_GE(q.z(), lo - 1e-9) << c.name;
      EXPECT_LE(q.z(), hi + 1e-9) << c.name;
    }
  }
}

// The defining property of a directional light's map: moving a point toward the light keeps its map
// position and brings its depth nearer (whatever the convention's depth order).
TEST(Lispsm, LightRaysStayParallelAndDepthFollowsThem) {
  const CascadeCamera camera = camera_looking(Vec3<double>(0.2, -0.1, -1));
  for (const RunConvention& c : kRunConventions) {
    const LightView v = fit_lispsm(c, kTowardSun, kBounds, camera, 1024).value().views.at(0);
    const bool reversed = near_ndc_z(c) > far_ndc_z(c);
    for (const Vec3<double>& p : seen_points(camera, 300)) {
      const Vec3<double> a = ndc(v, p), b = ndc(v, p + 3.0 * kTowardSun);
      EXPECT_NEAR(a.x(), b.x(), 1e-9) << c.name;
      EXPECT_NEAR(a.y(), b.y(), 1e-9) << c.name;
      EXPECT_TRUE(reversed ? b.z() > a.z() : b.z() < a.z()) << c.name << ": " << a.z() << " then " << b.z();
    }
  }
}

// The ground's size of one texel (along the map's x) at a point: near the camera it is far smaller
// than 150 m away, which is what the warp is for; the plain orthographic map (fit_light) has one
// size everywhere.
TEST(Lispsm, TexelsAreSmallNearTheCameraAndLargeFarFromIt) {
  const CascadeCamera camera = camera_looking(Vec3<double>(0, -0.03, -1));
  const LightView v = fit_lispsm(kDefaultConvention, kTowardSun, kBounds, camera, 1024).value().views.at(0);
  const auto texel_on_ground = [&](const Vec3<double>& p) {
    // Move along the ground (y = 0) until the map's x has moved by one texel (2 / 1024 in NDC).
    const Vec3<double> q = ndc(v, p);
    const Vec3<double> dx = ndc(v, p + Vec3<double>(1e-3, 0, 0)) - q, dz = ndc(v, p + Vec3<double>(0, 0, 1e-3)) - q;
    const double per_metre = std::hypot(dx.x(), dz.x()) / 1e-3;
    return (2.0 / 1024) / per_metre;
  };
  const double near_texel = texel_on_ground(Vec3<double>(0, 0, 5));
  const double far_texel = texel_on_ground(Vec3<double>(0, 0, -90));
  EXPECT_GT(far_texel, 3 * near_texel) << near_texel << " m near, " << far_texel << " m far";
}

// W keeps orientation: a triangle seen from the light winds the same way in the warped map as in
// the plain one, so a depth pass culling front faces culls the same faces.
TEST(Lispsm, ATriangleKeepsItsWinding) {
  const CascadeCamera camera = camera_looking(Vec3<double>(0, -0.2, -1));
  for (const RunConvention& c : kRunConventions) {
    const LightView warped = fit_lispsm(c, kTowardSun, kBounds, camera, 1024).value().views.at(0);
    const LightView plain = fit_lispsm(c, kTowardSun, kBounds, camera_looking(-kTowardSun), 1024).value().views.at(0);
    const std::array<Vec3<double>, 3> t{Vec3<double>(1, 0, 1), Vec3<double>(3, 0, 1), Vec3<double>(2, 0, -1)};
    const auto winding = [&](const LightView& v) {
      const Vec3<double> a = ndc(v, t[0]), b = ndc(v, t[1]), d = ndc(v, t[2]);
      return (b.x() - a.x()) * (d.y() - a.y()) - (b.y() - a.y()) * (d.x() - a.x()) > 0;
    };
    EXPECT_EQ(winding(warped), winding(plain)) << c.name;
  }
}

// A camera looking straight along the light has no axis to warp along: the plain orthographic map.
TEST(Lispsm, LookingAlongTheLightGivesThePlainMap) {
  for (const RunConvention& c : kRunConventions) {
    const LightView v = fit_lispsm(c, kTowardSun, kBounds, camera_looking(-kTowardSun), 512).value().views.at(0);
    EXPECT_EQ(v.projection.row(3), Vec4<double>(0, 0, 0, 1).transpose()) << c.name;
  }
}

TEST(Lispsm, BadInputIsRefused) {
  CascadeCamera camera = camera_looking(Vec3<double>(0, 0, -1));
  EXPECT_FALSE(fit_lispsm(kDefaultConvention, Vec3<double>::Zero(), kBounds, camera, 1024));
  EXPECT_FALSE(fit_lispsm(kDefaultConvention, kTowardSun, {kBounds[1], kBounds[0]}, camera, 1024));
  camera.near = 0;
  EXPECT_FALSE(fit_lispsm(kDefaultConvention, kTowardSun, kBounds, camera, 1024));
  camera.near = 0.1;
  camera.eye.x() = std::nan("");
  EXPECT_FALSE(fit_lispsm(kDefaultConvention, kTowardSun, kBounds, camera, 1024));
}

}  // namespace
}  // namespace shadowref
