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

// fit_cascades over generated cameras, suns and scenes (one cascade per visible point, no caster
// clipped, whole-texel moves): property_tests/cascade_properties_test.cpp. Here, the fixed cases.

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
