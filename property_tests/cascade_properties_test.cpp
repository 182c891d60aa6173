// cascade_properties_test.cpp — cascaded shadow maps (shadowref/cascades.hpp: fit_cascades and
// light_view_of) over generated suns, scene boxes and cameras, in every run convention:
//   * every point of the view frustum inside the scene's box falls in exactly one cascade, and
//     inside that cascade's window (short of the filter margin) and depth range — no gap, no point
//     left to no map;
//   * every corner of the scene's box lies inside every cascade's depth range: no caster between the
//     light and a cascade is clipped, whether or not the camera sees it;
//   * a camera translation moves every window by whole texels (static shadows do not shimmer), and
//     without snapping it generally does not (the property's own tooth).
#include <algorithm>
#include <array>
#include <cmath>

#include "generators.hpp"
#include "property_support.hpp"
#include "shadowref/cascades.hpp"

namespace shadowref::prop {
namespace {

struct CascadeCase {
  const RunConvention* conv = &kDefaultConvention;
  Vec3<double> toward;                 // toward the sun, above the horizon
  std::array<Vec3<double>, 2> bounds;  // a ground of half-size `half` and casters up to `top`
  CascadeCamera camera;
};

// Scenes from 5 to 500 units across; the camera 1–4 units above the ground somewhere over its middle
// half, looking roughly horizontally; a sun at least a few degrees up; lenses from 17 to 103 degrees.
rc::Gen<CascadeCase> cascade_case() {
  return rc::gen::exec([] {
    CascadeCase c;
    c.conv = &kRunConventions[static_cast<std::size_t>(*rc::gen::inRange<int>(0, 4))];
    c.toward = Vec3<double>(*gen::centered(1), *gen::uniform(0.05, 1), *gen::centered(1));
    const double half = *gen::uniform(5, 500), top = half * *gen::uniform(0.01, 0.2);
    c.bounds = {Vec3<double>(-half, 0, -half), Vec3<double>(half, top, half)};
    c.camera.eye = Vec3<double>(*gen::centered(half / 2), *gen::uniform(1, 4), *gen::centered(half / 2));
    c.camera.forward = Vec3<double>(*gen::centered(1), *gen::uniform(-0.4, 0.2), *gen::centered(1));
    RC_PRE(Vec2<double>(c.camera.forward.x(), c.camera.forward.z()).norm() > 0.1);
    c.camera.fovy = *gen::uniform(0.3, 1.8);
    c.camera.aspect = *gen::uniform(0.5, 2.5);
    c.camera.near = 0.1;
    return c;
  });
}

// The point of the camera's frustum at depth d, at (sx, sy) in [−1, 1]² across the view.
Vec3<double> frustum_point(const CascadeCamera& cam, double d, double sx, double sy) {
  const Vec3<double> f = cam.forward.normalized();
  const Vec3<double> right = f.cross(Vec3<double>(0, 1, 0)).normalized(), up = right.cross(f);
  const double ty = std::tan(cam.fovy / 2), tx = ty * cam.aspect;
  return cam.eye + d * (f + sx * tx * right + sy * ty * up);
}

// p in the light view's clip box (NDC x, y within 1 − inset, depth inside the convention's range).
bool inside(const LightView& v, const Vec3<double>& p, const RunConvention& conv, double inset) {
  const Vec4<double> c = v.projection * v.view * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
  const Vec3<double> q = c.head<3>() / c.w();
  const double lo = conv.clip.depth == DepthRange::NegOneToOne ? -1.0 : 0.0;
  return std::abs(q.x()) <= 1 - inset && std::abs(q.y()) <= 1 - inset && q.z() > lo && q.z() < 1;
}

TEST(CascadeProperties, every_visible_point_is_in_exactly_one_cascade_and_inside_its_window) {
  check_property([] {
    const CascadeCase c = *cascade_case();
    const LightFit fit = fit_cascades(*c.conv, c.toward, c.bounds, c.camera).value();
    RC_ASSERT(fit.views.size() == static_cast<std::size_t>(kDefaultCascades));
    const double far = fit.cascade_splits.back();
    // A depth log-uniform over [near, far] (the first cascades are thin) and a place across the view.
    const double d = c.camera.near * std::pow(far / c.camera.near, *gen::uniform(0, 1));
    const Vec3<double> p = frustum_point(c.camera, d, *gen::centered(1), *gen::centered(1));
    // Only where a surface may be: the map's depth range holds the scene, not the empty space around it.
    RC_PRE((p.array() >= c.bounds[0].array()).all() && (p.array() <= c.bounds[1].array()).all());
    const int view = light_view_of(fit, Vec4<double>(c.toward.x(), c.toward.y(), c.toward.z(), 0.0), p);
    RC_LOG() << c.conv->name << " depth " << d << " of [" << c.camera.near << ", " << far << "] cascade " << view << "\n";
    RC_ASSERT(view >= 0);
    int holding = 0;  // the cascades whose interval holds d, the last closed
    for (std::size_t i = 0; i + 1 < fit.cascade_splits.size(); ++i)
      holding += d >= fit.cascade_splits[i] &&
                 (i + 2 == fit.cascade_splits.size() ? d <= far : d < fit.cascade_splits[i + 1]);
    RC_ASSERT(holding == 1);
    RC_ASSERT(d >= fit.cascade_splits[static_cast<std::size_t>(view)]);
    // Inside its window, short of the margin kept for a filter's taps (a texel of rounding spare).
    const double margin_ndc = 2 * (kCascadeMarginTexels - 1) / fit.size;
    RC_ASSERT(inside(fit.views[static_cast<std::size_t>(view)], p, *c.conv, margin_ndc));
  });
}

TEST(CascadeProperties, no_caster_is_clipped_from_any_cascade) {
  check_property([] {
    const CascadeCase c = *cascade_case();
    const LightFit fit = fit_cascades(*c.conv, c.toward, c.bounds, c.camera).value();
    const int corner = *rc::gen::inRange(0, 8);
    const Vec3<double> p((corner & 1) ? c.bounds[1].x() : c.bounds[0].x(), (corner & 2) ? c.bounds[1].y() : c.bounds[0].y(),
                         (corner & 4) ? c.bounds[1].z() : c.bounds[0].z());
    for (const LightView& v : fit.views) {
      const Vec4<double> q = v.projection * v.view * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
      const double z = q.z() / q.w(), lo = c.conv->clip.depth == DepthRange::NegOneToOne ? -1.0 : 0.0;
      RC_LOG() << c.conv->name << " corner " << corner << " at depth " << z << "\n";
      RC_ASSERT(z > lo);
      RC_ASSERT(z < 1.0);
    }
  });
}

// The window's left edge, in texels of the view's own x (any convention: view-space x).
double window_left_in_texels(const LightView& v, int size) {
  const Mat4<double> inv = v.projection.inverse();
  const Vec4<double> left = inv * Vec4<double>(-1, 0, 0, 1);
  const double width = (inv * Vec4<double>(1, 0, 0, 1) - left).x();
  return left.x() / (width / size);
}

// The largest fractional part (distance to the nearest whole number of texels) by which a camera
// step moves any cascade's window, with or without snapping. The far end is pinned so that both
// cameras have the same slices, hence the same sphere radii and texel sizes.
double fractional_shift(const CascadeCase& c, const Vec3<double>& step, bool snap) {
  CascadeOptions o;
  o.snap = snap;
  o.map_size = 1024;
  CascadeCamera a = c.camera, b = c.camera;
  b.eye += step;
  a.far = b.far = 0.5 * (c.bounds[1] - c.bounds[0]).norm();
  const LightFit fa = fit_cascades(*c.conv, c.toward, c.bounds, a, o).value();
  const LightFit fb = fit_cascades(*c.conv, c.toward, c.bounds, b, o).value();
  double worst = 0;
  for (std::size_t i = 0; i < fa.views.size(); ++i) {
    const double shift = window_left_in_texels(fb.views[i], o.map_size) - window_left_in_texels(fa.views[i], o.map_size);
    worst = std::max(worst, std::abs(shift - std::round(shift)));
  }
  return worst;
}

TEST(CascadeProperties, a_camera_move_shifts_every_window_by_whole_texels) {
  check_property([] {
    const CascadeCase c = *cascade_case();
    const Vec3<double> step(*gen::centered(3), 0, *gen::centered(3));
    const double fraction = fractional_shift(c, step, true);
    RC_LOG() << c.conv->name << " step (" << step.x() << ", " << step.z() << "): off whole texels by " << fraction << "\n";
    // Whole texels up to the rounding of the window's edges, hundreds of texels from the origin.
    RC_ASSERT(fraction < 1e-4);
  });
}

// The property's tooth: the same cameras without snapping move windows by fractions of a texel
// (a counterexample must turn up within this many cases; almost every case is one).
constexpr int kCascadeTeethCases = 100;
TEST(CascadeProperties, without_snapping_windows_move_by_fractions_of_a_texel) {
  expect_counterexample([] {
    const CascadeCase c = *cascade_case();
    const Vec3<double> step(*gen::centered(3), 0, *gen::centered(3));
    RC_ASSERT(fractional_shift(c, step, false) < 1e-4);
  }, kCascadeTeethCases);
}

}  // namespace
}  // namespace shadowref::prop
