// cascades_test.cpp — cascades.hpp: the practical split scheme against its two limits, every view
// depth in exactly one cascade, the slice sphere holding its frustum slice (and being the smallest
// such sphere on the axis), and texel snapping moving a cascade only by whole texels.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "shadowref/cascades.hpp"

namespace shadowref {
namespace {

TEST(CascadeSplits, LambdaZeroIsUniformAndOneIsLogarithmic) {
  const auto u = cascade_splits(1.0, 101.0, 4, 0.0).value();
  const auto l = cascade_splits(1.0, 10000.0, 4, 1.0).value();
  for (int i = 0; i <= 4; ++i) {
    EXPECT_NEAR(u[i], 1.0 + 25.0 * i, 1e-12);
    EXPECT_NEAR(l[i], std::pow(10.0, i), 1e-9 * std::pow(10.0, i));  // 1, 10, 100, 1000, 10000
  }
}

TEST(CascadeSplits, EndsAreExactAndSplitsIncrease) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> near(0.01, 10.0), ratio(1.001, 1e5), lambda(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const double n = near(rng), f = n * ratio(rng);
    const int count = 1 + k % kMaxCascades;
    const auto s = cascade_splits(n, f, count, lambda(rng)).value();
    ASSERT_EQ(s.size(), static_cast<std::size_t>(count) + 1);
    EXPECT_EQ(s.front(), n);
    EXPECT_EQ(s.back(), f);
    for (int i = 0; i < count; ++i) EXPECT_LT(s[i], s[i + 1]) << n << " " << f << " " << count;
  }
}

// Every depth of [near, far] is in exactly one cascade: the one cascade_of names, whose interval
// holds it; nothing outside is in any.
TEST(CascadeSplits, EveryDepthFallsInExactlyOneCascade) {
  const auto s = cascade_splits(0.5f, 500.0f, 4, 0.75f).value();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> depth(0.5f, 500.0f);
  for (int k = 0; k < 20000; ++k) {
    const float d = k < 5 ? s[static_cast<std::size_t>(k)] : depth(rng);  // the splits themselves too
    const int c = cascade_of(s, d);
    ASSERT_GE(c, 0) << d;
    int holding = 0;
    for (int i = 0; i < 4; ++i) {
      const bool last = i == 3;
      holding += d >= s[i] && (last ? d <= s[i + 1] : d < s[i + 1]);
    }
    EXPECT_EQ(holding, 1) << d;
    EXPECT_TRUE(d >= s[c] && d <= s[c + 1]) << d << " in cascade " << c;
  }
  EXPECT_EQ(cascade_of(s, 0.49f), -1);
  EXPECT_EQ(cascade_of(s, 500.5f), -1);
  EXPECT_EQ(cascade_of(s, std::nanf("")), -1);
}

TEST(CascadeSplits, BadInputIsRefused) {
  EXPECT_EQ(cascade_splits(0.0, 10.0, 4, 0.5).error(), Error::NearNotPositive);
  EXPECT_EQ(cascade_splits(1.0, 1.0, 4, 0.5).error(), Error::FarNotBeyondNear);
  EXPECT_EQ(cascade_splits(1.0, 10.0, 0, 0.5).error(), Error::CascadeCountOutOfRange);
  EXPECT_EQ(cascade_splits(1.0, 10.0, kMaxCascades + 1, 0.5).error(), Error::CascadeCountOutOfRange);
  EXPECT_EQ(cascade_splits(1.0, 10.0, 4, 1.5).error(), Error::SplitWeightOutOfRange);
  EXPECT_EQ(cascade_splits(1.0, std::numeric_limits<double>::infinity(), 4, 0.5).error(), Error::NonFinite);
}

// The sphere holds all eight corners of the slice (and so the whole convex slice), its radius is
// that of the farthest corner, and no point of the axis gives a smaller sphere.
TEST(SliceSphere, HoldsTheSliceAndIsTheSmallestOnTheAxis) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> fov(0.1, 2.8), aspect(0.3, 3.0), d0(0.05, 50.0), ratio(1.01, 100.0);
  for (int k = 0; k < 5000; ++k) {
    const double f = fov(rng), a = aspect(rng), n = d0(rng), fa = n * ratio(rng);
    const SliceSphere<double> s = slice_bounding_sphere(f, a, n, fa).value();
    const double ty = std::tan(f / 2), tx = ty * a;
    double farthest = 0;
    for (double d : {n, fa})
      for (int sx : {-1, 1})
        for (int sy : {-1, 1}) {
          const double x = sx * tx * d, y = sy * ty * d, z = d - s.centre_depth;
          farthest = std::max(farthest, std::sqrt(x * x + y * y + z * z));
        }
    EXPECT_LE(farthest, s.radius * (1 + 1e-12)) << f << " " << a << " " << n << " " << fa;
    EXPECT_NEAR(farthest, s.radius, 1e-9 * s.radius);
    // Moving the centre along the axis either way makes the needed radius larger.
    for (double step : {-1e-3, 1e-3}) {
      const double c = s.centre_depth + step * s.radius;
      double need = 0;
      for (double d : {n, fa}) need = std::max(need, std::hypot(tx * d, ty * d, d - c));
      EXPECT_GE(need, s.radius * (1 - 1e-12));
    }
  }
}

// Stability: the radius depends on the lens and the depths only, so a camera that moves or turns
// keeps its cascades' texel size; snapped centres then move by whole texels only.
TEST(SnapToTexels, MovesACascadeByWholeTexelsOnly) {
  const SliceSphere<double> s = slice_bounding_sphere(1.0, 16.0 / 9.0, 10.0, 40.0).value();
  const int map = 2048;
  const double texel = 2 * s.radius / map;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-1000.0, 1000.0);
  for (int k = 0; k < 10000; ++k) {
    const Vec2<double> a(pos(rng), pos(rng)), b(pos(rng), pos(rng));
    const Vec2<double> sa = snap_to_texels(a, s.radius, map), sb = snap_to_texels(b, s.radius, map);
    for (int i = 0; i < 2; ++i) {
      const double moved = (sb[i] - sa[i]) / texel;
      EXPECT_NEAR(moved, std::round(moved), 1e-6) << "moved by a fraction of a texel";
      EXPECT_LE(std::abs(sa[i] - a[i]), texel / 2 * (1 + 1e-9));  // within half a texel of the true centre
    }
  }
}

// fit_cascades, over random cameras, suns and scene boxes in every run convention:
//   * every point of the view frustum inside the scene box falls in exactly one cascade
//     (light_view_of), and inside that cascade's window and depth range — no gap, no point left out;
//   * every corner of the scene box lies inside every cascade's depth range: no caster between the
//     light and a cascade is clipped, whether or not the camera sees it;
//   * translating the camera moves each window by whole texels of its map (static shadows do not
//     shimmer), and without snapping it does not.
struct FitCase {
  const RunConvention* conv;
  Vec3<double> toward;
  std::array<Vec3<double>, 2> bounds;
  CascadeCamera camera;
};

FitCase random_case(std::mt19937& rng, int k) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(5.0, 500.0), fov(0.3, 1.8), aspect(0.5, 2.5);
  FitCase c;
  c.conv = &kRunConventions[static_cast<std::size_t>(k) % kRunConventions.size()];
  do c.toward = Vec3<double>(u(rng), std::abs(u(rng)) + 0.05, u(rng)); while (c.toward.norm() < 0.1);
  const double half = size(rng);
  c.bounds = {Vec3<double>(-half, 0, -half), Vec3<double>(half, half * 0.1 * (1 + u(rng)), half)};
  c.camera.eye = Vec3<double>(u(rng) * half * 0.5, 1 + std::abs(u(rng)) * 3, u(rng) * half * 0.5);
  do c.camera.forward = Vec3<double>(u(rng), u(rng) * 0.3 - 0.1, u(rng)); while (c.camera.forward.norm() < 0.1);
  c.camera.fovy = fov(rng);
  c.camera.aspect = aspect(rng);
  c.camera.near = 0.1;
  return c;
}

// The point of the frustum at camera depth d, at NDC-like (sx, sy) in [-1, 1] across the view.
Vec3<double> frustum_point(const CascadeCamera& cam, double d, double sx, double sy) {
  const Vec3<double> f = cam.forward.normalized();
  const Vec3<double> right = f.cross(Vec3<double>(0, 1, 0)).normalized(), up = right.cross(f);
  const double ty = std::tan(cam.fovy / 2), tx = ty * cam.aspect;
  return cam.eye + d * (f + sx * tx * right + sy * ty * up);
}

bool inside_view(const LightView& v, const Vec3<double>& p, const RunConvention& conv, double slack) {
  const Vec4<double> c = v.projection * v.view * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
  const Vec3<double> q = c.head<3>() / c.w();
  const double lo = conv.clip.depth == DepthRange::NegOneToOne ? -1.0 : 0.0;
  return std::abs(q.x()) <= 1 + slack && std::abs(q.y()) <= 1 + slack && q.z() >= lo - slack && q.z() <= 1 + slack;
}

TEST(FitCascades, EveryVisiblePointIsInExactlyOneCascadeAndInsideItsWindow) {
  std::mt19937 rng(17);
  int checked = 0;
  std::uniform_real_distribution<double> s(-1.0, 1.0), t(0.0, 1.0);
  for (int k = 0; k < 400; ++k) {
    const FitCase c = random_case(rng, k);
    const LightFit fit = fit_cascades(*c.conv, c.toward, c.bounds, c.camera).value();
    ASSERT_EQ(fit.views.size(), static_cast<std::size_t>(kDefaultCascades));
    const double far = fit.cascade_splits.back();
    for (int n = 0; n < 200; ++n) {
      const double d = c.camera.near * std::pow(far / c.camera.near, t(rng));
      const Vec3<double> p = frustum_point(c.camera, d, s(rng), s(rng));
      // Only where there may be a surface: the map's depth range holds the scene, not empty space.
      if ((p.array() < c.bounds[0].array()).any() || (p.array() > c.bounds[1].array()).any()) continue;
      ++checked;
      const int view = light_view_of(fit, Vec4<double>(c.toward.x(), c.toward.y(), c.toward.z(), 0.0), p);
      ASSERT_GE(view, 0) << "depth " << d << " of [" << c.camera.near << ", " << far << "] in no cascade";
      int holding = 0;
      for (std::size_t i = 0; i + 1 < fit.cascade_splits.size(); ++i)
        holding += d >= fit.cascade_splits[i] * (1 - 1e-12) &&
                   (i + 2 == fit.cascade_splits.size() ? d <= far * (1 + 1e-12) : d < fit.cascade_splits[i + 1]);
      EXPECT_EQ(holding, 1) << d;
      // Inside its cascade's window, short of the margin kept for a filter's taps.
      EXPECT_TRUE(inside_view(fit.views[static_cast<std::size_t>(view)], p, *c.conv, -kCascadeMarginTexels / fit.size))
          << "case " << k << ": a point at depth " << d << " outside cascade " << view << "'s window";
    }
  }
  EXPECT_GT(checked, 5000) << "too few frustum points inside the scene boxes to prove anything";
}

TEST(FitCascades, NoCasterIsClippedFromAnyCascade) {
  std::mt19937 rng(19);
  for (int k = 0; k < 400; ++k) {
    const FitCase c = random_case(rng, k);
    const LightFit fit = fit_cascades(*c.conv, c.toward, c.bounds, c.camera).value();
    for (const LightView& v : fit.views)
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3<double> p((corner & 1) ? c.bounds[1].x() : c.bounds[0].x(), (corner & 2) ? c.bounds[1].y() : c.bounds[0].y(),
                             (corner & 4) ? c.bounds[1].z() : c.bounds[0].z());
        const Vec4<double> q = v.projection * v.view * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
        const double z = q.z() / q.w(), lo = c.conv->clip.depth == DepthRange::NegOneToOne ? -1.0 : 0.0;
        EXPECT_TRUE(z > lo && z < 1) << "case " << k << ": a corner of the scene at depth " << z << " is clipped";
      }
    // The fault the renderer's teeth use: depth ranges fitted to the slices clip some caster.
  }
}

// The window's left edge in texels of the light view's x (any convention: x of view space).
double window_left_in_texels(const LightView& v, int size) {
  const Mat4<double> inv = v.projection.inverse();
  const Vec4<double> left = inv * Vec4<double>(-1, 0, 0, 1);
  const double width = (inv * Vec4<double>(1, 0, 0, 1) - left).x();
  return left.x() / (width / size);
}

TEST(FitCascades, ACameraMoveShiftsEveryWindowByWholeTexels) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> step(-3.0, 3.0);
  int unsnapped_fractional = 0;
  for (int k = 0; k < 200; ++k) {
    FitCase c = random_case(rng, k);
    CascadeCamera moved = c.camera;
    moved.eye += Vec3<double>(step(rng), 0, step(rng));
    for (const bool snap : {true, false}) {
      CascadeOptions o;
      o.snap = snap;
      o.map_size = 1024;
      // Same far end for both cameras, so the slices (and so the radii) are the same.
      c.camera.far = moved.far = 0.5 * (c.bounds[1] - c.bounds[0]).norm();
      const LightFit a = fit_cascades(*c.conv, c.toward, c.bounds, c.camera, o).value();
      const LightFit b = fit_cascades(*c.conv, c.toward, c.bounds, moved, o).value();
      for (std::size_t i = 0; i < a.views.size(); ++i) {
        const double shift = window_left_in_texels(b.views[i], o.map_size) - window_left_in_texels(a.views[i], o.map_size);
        const double fraction = std::abs(shift - std::round(shift));
        if (snap) EXPECT_LT(fraction, 1e-4) << "case " << k << " cascade " << i << " moved by " << shift << " texels";
        else unsnapped_fractional += fraction > 1e-3;
      }
    }
  }
  // The check has teeth: without snapping, windows move by fractions of a texel.
  EXPECT_GT(unsnapped_fractional, 400);
}

TEST(FitCascades, SliceDepthRangesClipCastersOutsideTheSlice) {
  // A tall caster behind the camera, toward a sun behind it: inside the scene's depth range, outside
  // the first slice's sphere (what the csm-caster-clipped-from-cascade tooth relies on).
  const RunConvention& conv = kDefaultConvention;
  CascadeCamera cam;
  cam.eye = Vec3<double>(0, 2, 10);
  cam.forward = Vec3<double>(0, 0, -1);
  cam.fovy = 0.87;
  const std::array<Vec3<double>, 2> bounds{Vec3<double>(-300, 0, -300), Vec3<double>(300, 12, 300)};
  const Vec3<double> toward(-0.45, 0.3, 0.9), top(-10, 12, 24);
  CascadeOptions o;
  const LightFit right = fit_cascades(conv, toward, bounds, cam, o).value();
  o.scene_depth_range = false;
  const LightFit clipped = fit_cascades(conv, toward, bounds, cam, o).value();
  const auto depth = [&](const LightView& v) {
    const Vec4<double> q = v.projection * v.view * Vec4<double>(top.x(), top.y(), top.z(), 1.0);
    return q.z() / q.w();
  };
  EXPECT_GT(depth(right.views[0]), -1.0);
  EXPECT_LT(depth(clipped.views[0]), -1.0) << "the tower top should lie before the slice-only near plane";
}

TEST(FitCascades, BadInputIsRefused) {
  const std::array<Vec3<double>, 2> box{Vec3<double>(-1, 0, -1), Vec3<double>(1, 1, 1)};
  CascadeCamera cam;
  EXPECT_EQ(fit_cascades(kDefaultConvention, Vec3<double>(0, 0, 0), box, cam).error(), Error::NonFinite);
  cam.near = 0;
  EXPECT_EQ(fit_cascades(kDefaultConvention, Vec3<double>(0, 1, 0), box, cam).error(), Error::NearNotPositive);
  cam.near = 0.1;
  CascadeOptions o;
  o.count = 0;
  EXPECT_EQ(fit_cascades(kDefaultConvention, Vec3<double>(0, 1, 0), box, cam, o).error(), Error::CascadeCountOutOfRange);
  const std::array<Vec3<double>, 2> inverted{Vec3<double>(1, 0, 1), Vec3<double>(-1, 1, -1)};
  EXPECT_EQ(fit_cascades(kDefaultConvention, Vec3<double>(0, 1, 0), inverted, cam).error(), Error::EmptyMesh);
}

}  // namespace
}  // namespace shadowref
