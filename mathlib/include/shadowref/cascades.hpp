// shadowref/cascades.hpp — cascaded shadow maps for a directional light: where the view frustum is
// split, the sphere that holds each slice, and the texel snapping that keeps static shadows still
// while the camera moves. Convention-free: distances are along the camera's viewing direction
// (positive, as `near` and `far` of perspective()), light space is any orthonormal basis of the
// light's view; the caller builds the matrices (light_fit.hpp, convention.hpp).
//
//   * cascade_splits: the practical split scheme of Zhang et al. 2006 ("Parallel-split shadow maps
//     for large-scale virtual environments"): split_i = λ·n·(f/n)^(i/N) + (1−λ)·(n + (f−n)·i/N),
//     a blend of the logarithmic scheme (λ = 1: equal texel density per depth ratio) and the
//     uniform one (λ = 0). N + 1 distances, split_0 = n, split_N = f, strictly increasing.
//   * cascade_of: the cascade a view depth falls in — every depth in [n, f] in exactly one:
//     [split_i, split_{i+1}) for i < N − 1, the last cascade closed at f.
//   * slice_bounding_sphere: the smallest sphere holding the frustum slice between two depths of a
//     symmetric perspective camera (fovy, aspect). It depends on the depths and the lens only, not
//     on the camera's position or orientation, so its radius — and with it the cascade's texel size
//     — does not change as the camera turns: the "stable" fit (Valient 2007, ShaderX6, "Stable
//     rendering of cascaded shadow maps"). Centre on the viewing axis at distance `centre_depth`.
//   * snap_to_texels: a light-space position rounded to whole texels (texel = 2 r / map size), the
//     other half of that stability: the orthographic window then moves in whole texels, so every
//     texel keeps sampling the same world points and static edges do not shimmer.
//   * fit_cascades: the cascaded shadow map of a directional light for a camera — the splits of
//     [camera near, min(camera far, the farthest point of the scene's box ahead)], and per cascade
//     one orthographic view (a LightFit whose views are the cascades, light_fit.hpp): the slice's
//     bounding sphere, its centre snapped to whole texels in a light space fixed to the scene (not
//     to the camera), and a depth range holding the whole scene's bounding sphere, so that a caster
//     between the light and a cascade is drawn into it even when it lies outside the camera's view
//     and outside the slice. Every view shares one orientation and one depth range; only the window
//     differs. Convention: the run convention's view and projection (convention.hpp), as fit_light.
//   * light_view_of: which view of a fit decides a scene point (cube face, cascade, or the one view).
// Cost: O(N) and O(1); fit_cascades O(N) after the scene's bounds. Errors: NonFinite,
// NearNotPositive, FarNotBeyondNear, CascadeCountOutOfRange, SplitWeightOutOfRange, FovOutOfRange,
// ZeroAspect.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "shadowref/conventions.hpp"
#include "shadowref/light_fit.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

inline constexpr int kMaxCascades = 8;
// The defaults of fit_cascades: four cascades (what engines ship for a sun), split three quarters
// logarithmic: with the cascades reaching to the scene's far end, an even blend gives the first
// cascade a quarter of the whole depth and leaves the ground at the camera's feet coarse.
inline constexpr int kDefaultCascades = 4;
inline constexpr double kDefaultSplitWeight = 0.75;
// Each cascade's window is its slice's sphere widened by this many texels on every side, so that a
// filter's taps around a point of the slice stay inside the map (the sphere may touch the window).
inline constexpr double kCascadeMarginTexels = 2.0;

// The N + 1 split distances of the practical scheme (see above), weight `lambda` in [0, 1].
template <class T>
Result<std::vector<T>> cascade_splits(T near, T far, int count, T lambda) {
  if (!std::isfinite(near) || !std::isfinite(far) || !std::isfinite(lambda)) return Error::NonFinite;
  if (!(near > T(0))) return Error::NearNotPositive;
  if (!(far > near)) return Error::FarNotBeyondNear;
  if (count < 1 || count > kMaxCascades) return Error::CascadeCountOutOfRange;
  if (!(lambda >= T(0) && lambda <= T(1))) return Error::SplitWeightOutOfRange;
  std::vector<T> s(static_cast<std::size_t>(count) + 1);
  for (int i = 0; i <= count; ++i) {
    const T t = T(i) / T(count);
    const T log_split = near * std::pow(far / near, t);
    const T uniform_split = near + (far - near) * t;
    s[static_cast<std::size_t>(i)] = lambda * log_split + (T(1) - lambda) * uniform_split;
  }
  s.front() = near;  // exact ends, whatever the rounding of pow
  s.back() = far;
  return s;
}

// The cascade holding view depth `depth` (in [splits.front(), splits.back()]), or -1 outside.
template <class T>
int cascade_of(const std::vector<T>& splits, T depth) {
  const int n = static_cast<int>(splits.size()) - 1;
  if (n < 1 || !(depth >= splits.front()) || !(depth <= splits.back())) return -1;
  for (int i = 0; i < n - 1; ++i)
    if (depth < splits[static_cast<std::size_t>(i) + 1]) return i;
  return n - 1;
}

template <class T>
struct SliceSphere {
  T centre_depth;  // distance of the centre along the viewing axis from the eye
  T radius;
};

// The smallest sphere holding the slice d0 <= depth <= d1 of a symmetric perspective frustum with
// vertical field of view `fovy` (radians) and `aspect` = width / height. The slice's corners lie
// on two circles around the axis, of radii k·d0 and k·d1 with k = tan(fovy/2)·sqrt(1 + aspect²);
// the sphere through both has its centre at z = (d0 + d1)/2 + k²(d1² − d0²) / (2 (d1 − d0)),
// clamped to d1 when that lies beyond the far circle (then the far circle alone bounds it).
template <class T>
Result<SliceSphere<T>> slice_bounding_sphere(T fovy, T aspect, T d0, T d1) {
  if (!std::isfinite(fovy) || !std::isfinite(aspect) || !std::isfinite(d0) || !std::isfinite(d1)) return Error::NonFinite;
  if (!(fovy > T(0) && fovy < T(3.14159265358979323846))) return Error::FovOutOfRange;
  if (!(aspect > T(0))) return Error::ZeroAspect;
  if (!(d0 > T(0))) return Error::NearNotPositive;
  if (!(d1 > d0)) return Error::FarNotBeyondNear;
  const T k2 = std::tan(fovy / T(2)) * std::tan(fovy / T(2)) * (T(1) + aspect * aspect);
  T z = (d0 + d1) / T(2) + k2 * (d1 * d1 - d0 * d0) / (T(2) * (d1 - d0));
  if (z > d1) z = d1;
  const T r = std::sqrt(k2 * d1 * d1 + (d1 - z) * (d1 - z));
  const T r_near = std::sqrt(k2 * d0 * d0 + (z - d0) * (z - d0));
  return SliceSphere<T>{z, r > r_near ? r : r_near};
}

// `p` (light-space x and y of a cascade's centre) rounded to whole texels of a map of `map_size`
// texels across 2·radius.
template <class T>
Vec2<T> snap_to_texels(const Vec2<T>& p, T radius, int map_size) {
  const T texel = T(2) * radius / T(map_size);
  return Vec2<T>(std::round(p.x() / texel) * texel, std::round(p.y() / texel) * texel);
}

// The camera a cascaded map is fitted to: a symmetric perspective camera in scene space.
struct CascadeCamera {
  Vec3<double> eye = Vec3<double>::Zero();
  Vec3<double> forward = Vec3<double>(0, 0, -1);  // the viewing direction (normalised by the fit)
  double fovy = 0.785398;                         // vertical field of view, radians
  double aspect = 1;                              // width / height
  double near = 0.1;
  double far = std::numeric_limits<double>::infinity();  // infinite: the scene's farthest point ahead
};

struct CascadeOptions {
  int count = kDefaultCascades;
  double split_weight = kDefaultSplitWeight;  // lambda of cascade_splits
  int map_size = kDirectionalAutoSize;        // texels per side of each cascade's map
  // Whole texels (false: the window follows the camera continuously, and edges shimmer as it moves).
  bool snap = true;
  // Each view's depth range holds the whole scene (false: only the slice's sphere, which clips the
  // casters between the light and the slice that lie outside it: shadows go missing).
  bool scene_depth_range = true;
};

// The cascades of the directional light toward `toward_light` (from the scene to the light) over
// the scene box `bounds` ({min, max}) for `camera`, in the run convention `conv` (see above).
inline Result<LightFit> fit_cascades(const RunConvention& conv, const Vec3<double>& toward_light,
                                     const std::array<Vec3<double>, 2>& bounds, const CascadeCamera& camera,
                                     const CascadeOptions& o = {}) {
  if (!toward_light.allFinite() || !bounds[0].allFinite() || !bounds[1].allFinite() || !camera.eye.allFinite() ||
      !camera.forward.allFinite() || std::isnan(camera.far))
    return Error::NonFinite;
  if (!(toward_light.norm() > 0) || !(camera.forward.norm() > 0)) return Error::NonFinite;
  if (!(bounds[0].x() <= bounds[1].x() && bounds[0].y() <= bounds[1].y() && bounds[0].z() <= bounds[1].z()))
    return Error::EmptyMesh;
  if (!(camera.near > 0)) return Error::NearNotPositive;
  if (o.map_size < 1) return Error::NonFinite;
  const Vec3<double> toward = toward_light.normalized(), forward = camera.forward.normalized();
  // The depths the cascades cover: the camera's near plane to its far plane or the farthest corner
  // of the scene's box ahead of it, whichever is nearer (nothing beyond needs a texel).
  double farthest = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3<double> c((k & 1) ? bounds[1].x() : bounds[0].x(), (k & 2) ? bounds[1].y() : bounds[0].y(),
                         (k & 4) ? bounds[1].z() : bounds[0].z());
    farthest = std::max(farthest, (c - camera.eye).dot(forward));
  }
  double far = std::min(camera.far, farthest);
  if (!(far > camera.near * (1 + 1e-9))) far = 2 * camera.near;  // nothing ahead: any range will do
  auto splits = cascade_splits(camera.near, far, o.count, o.split_weight);
  if (!splits) return splits.error();
  // Light space fixed to the scene: looking along −toward at the box's centre from 2 R away, so
  // that the whole box lies at depths [R, 3 R] (R its bounding radius), as fit_light's single view.
  const Vec3<double> centre = 0.5 * (bounds[0] + bounds[1]);
  const double R = std::max(0.5 * (bounds[1] - bounds[0]).norm(), 1e-6);
  auto view = view_from_scene<double>(conv, centre + toward * (2 * R), centre, least_aligned_axis(toward));
  if (!view) return view.error();
  const double axis_sign = conv.clip.hand == Handedness::Right ? -1.0 : 1.0;  // view-space z → depth
  LightFit fit;
  fit.size = o.map_size;
  fit.cascade_splits = *splits;
  fit.cascade_depth_from_scene << forward, -forward.dot(camera.eye);
  for (int i = 0; i < o.count; ++i) {
    const auto sphere = slice_bounding_sphere(camera.fovy, camera.aspect, (*splits)[i], (*splits)[i + 1]);
    if (!sphere) return sphere.error();
    const double r = o.map_size > 8 * kCascadeMarginTexels
                         ? sphere->radius * o.map_size / (o.map_size - 2 * kCascadeMarginTexels)
                         : sphere->radius;
    const Vec3<double> c = camera.eye + forward * sphere->centre_depth;
    const Vec4<double> q = *view * Vec4<double>(c.x(), c.y(), c.z(), 1.0);
    Vec2<double> xy(q.x(), q.y());
    if (o.snap) xy = snap_to_texels(xy, r, o.map_size);
    double near = 0.5 * R, far_depth = 3.5 * R;
    if (!o.scene_depth_range) {
      near = axis_sign * q.z() - r;
      far_depth = axis_sign * q.z() + r;
    }
    auto projection = ortho_for<double>(conv, xy.x() - r, xy.x() + r, xy.y() - r, xy.y() + r, near, far_depth);
    if (!projection) return projection.error();
    LightView v;
    v.view = *view;
    v.projection = *projection;
    fit.views.push_back(std::move(v));
  }
  return fit;
}

// The view of `fit` that decides the scene point `p` for the light L (homogeneous): the cube face
// of the largest component of p − light (a cube-map lookup); the cascade holding p's camera depth,
// the first and the last open-ended (a depth before the near plane or beyond the scene's far end
// is only rounding: the last split is the farthest point of the scene ahead); or the one view.
// The renderer's shader makes the same choice.
inline int light_view_of(const LightFit& fit, const Vec4<double>& L, const Vec3<double>& p) {
  if (fit.cube) {
    const Vec3<double> dp = p - L.head<3>() / L.w();
    const Vec3<double> a = dp.cwiseAbs();
    if (a.x() >= a.y() && a.x() >= a.z()) return dp.x() >= 0 ? 0 : 1;
    if (a.y() >= a.z()) return dp.y() >= 0 ? 2 : 3;
    return dp.z() >= 0 ? 4 : 5;
  }
  if (fit.cascade_splits.size() >= 2) {
    const double depth = fit.cascade_depth_from_scene.dot(Vec4<double>(p.x(), p.y(), p.z(), 1.0));
    return cascade_of(fit.cascade_splits, std::clamp(depth, fit.cascade_splits.front(), fit.cascade_splits.back()));
  }
  return 0;
}

}  // namespace shadowref
