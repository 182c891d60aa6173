// shadowref/lispsm.hpp — light space perspective shadow maps (Wimmer, Scherzer and Purgathofer
// 2004, "Light Space Perspective Shadow Maps", EGSR): a directional light's one map, warped by a
// perspective whose axis is the camera's viewing direction as the light sees it, so that texels
// are small near the camera and grow with distance from it — the texel density a camera needs,
// from one map. Convention: the run convention's view and projection (convention.hpp), as fit_light.
//
//   * fit_lispsm: the LightFit (one view) of the directional light toward `toward_light` over the
//     scene box `bounds` for `camera`, with `map_size` texels per side.
//       view: a look-at along the light whose up vector is the camera's forward direction with its
//         component along the light removed (light-view y: the warp's axis).
//       the body: where the camera can see a shadow, bounded in light-view x and y by the overlap
//         of the scene's box and the camera frustum's (out to the farthest scene point ahead, the
//         frustum's cross-sections bounded by their circumscribed circles), and in depth by the
//         whole scene box, so that a caster outside the camera's view still reaches the map.
//       projection: ortho_for(conv, ...) · W. W is the paper's perspective along light-view y from
//         an eye n below the body's nearest y: with w = y − y0 + n, W takes (x, y, z) to
//         ((x − e_x) / w, (a w + b) / w, z / w), a = (f + n) / (f − n), b = −2 f n / (f − n),
//         f = n + d, d the body's extent along y and e_x the camera's light-view x; n is the paper's
//         n_opt = (z_n + sqrt(z_n z_f)) / sin γ, z_n = near / sin γ, z_f = z_n + d sin γ, γ the angle
//         between the camera's forward direction and the light's. The orthographic projection then
//         fits W's image of the body: x and depth (z / w, along the light) to their extremes, y to
//         [−1, 1], which W's a and b already give.
//     Light rays stay parallel through W (they run along light-view z, parallel to W's image plane,
//     and w is constant along each), so the map is still a directional light's: a scene point and
//     every point along the light from it share one texel, and depth order along a ray is kept.
//     W keeps orientation (its Jacobian is triangular with positive diagonal where w > 0), so a
//     depth pass culls the faces it would cull without the warp.
//     Where the camera looks (nearly) along the light (sin γ < kLispsmMinSinGamma) there is no axis
//     to warp along and n_opt runs to infinity: the plain orthographic projection of the body.
// Cost: O(1). Errors: NonFinite, EmptyMesh, NearNotPositive, and those of view_from_scene and
// ortho_for.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "shadowref/cascades.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/light_fit.hpp"

namespace shadowref {

// Below this sin γ (about 3 degrees between the camera's forward direction and the light's) the warp
// is dropped: the paper's n_opt grows as 1 / sin² γ, and the warp it gives tends to none at all.
inline constexpr double kLispsmMinSinGamma = 0.05;

// A share of the body's depth span added before and beyond it, so that the nearest caster and the
// farthest receiver do not lie on the map's near and far planes, where float rounding could clip them.
inline constexpr double kLispsmDepthMargin = 0.01;

inline Result<LightFit> fit_lispsm(const RunConvention& conv, const Vec3<double>& toward_light,
                                   const std::array<Vec3<double>, 2>& bounds, const CascadeCamera& camera,
                                   int map_size) {
  if (!toward_light.allFinite() || !bounds[0].allFinite() || !bounds[1].allFinite() || !camera.eye.allFinite() ||
      !camera.forward.allFinite() || std::isnan(camera.far) || !std::isfinite(camera.fovy) || !std::isfinite(camera.aspect))
    return Error::NonFinite;
  if (!(toward_light.norm() > 0) || !(camera.forward.norm() > 0) || map_size < 1) return Error::NonFinite;
  if (!(bounds[0].x() <= bounds[1].x() && bounds[0].y() <= bounds[1].y() && bounds[0].z() <= bounds[1].z()))
    return Error::EmptyMesh;
  if (!(camera.near > 0)) return Error::NearNotPositive;
  const Vec3<double> toward = toward_light.normalized(), forward = camera.forward.normalized();
  const double cos_gamma = -forward.dot(toward);  // forward · (the light's direction into the scene)
  const double sin_gamma = std::sqrt(std::max(0.0, 1.0 - cos_gamma * cos_gamma));
  Vec3<double> up = forward + cos_gamma * toward;  // forward less its component along the light
  if (!(up.norm() > 1e-9)) up = least_aligned_axis(toward);

  // Light view, fixed to the scene as fit_light's: the box's centre from 2 R along the light.
  const Vec3<double> centre = 0.5 * (bounds[0] + bounds[1]);
  const double R = std::max(0.5 * (bounds[1] - bounds[0]).norm(), 1e-6);
  const Result<Mat4<double>> view = view_from_scene<double>(conv, centre + toward * (2 * R), centre, up.normalized());
  if (!view) return view.error();
  const auto to_view = [&](const Vec3<double>& p) -> Vec3<double> {
    return (*view * Vec4<double>(p.x(), p.y(), p.z(), 1.0)).head<3>();
  };
  Vec3<double> scene_lo = Vec3<double>::Constant(std::numeric_limits<double>::infinity()), scene_hi = -scene_lo;
  double farthest = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3<double> c((k & 1) ? bounds[1].x() : bounds[0].x(), (k & 2) ? bounds[1].y() : bounds[0].y(),
                         (k & 4) ? bounds[1].z() : bounds[0].z());
    const Vec3<double> q = to_view(c);
    scene_lo = scene_lo.cwiseMin(q);
    scene_hi = scene_hi.cwiseMax(q);
    farthest = std::max(farthest, (c - camera.eye).dot(forward));
  }
  // The frustum's box in light-view x and y: its cross-sections at the near plane and at the
  // farthest scene point ahead, each inside the circle through its corners.
  double far = std::min(camera.far, farthest);
  if (!(far > camera.near)) far = 2 * camera.near;
  const double tan_diagonal = std::tan(0.5 * camera.fovy) * std::sqrt(1.0 + camera.aspect * camera.aspect);
  const Vec3<double> forward_view = view->topLeftCorner<3, 3>() * forward;  // the view holds the world's mirror
  Vec3<double> frustum_lo = Vec3<double>::Constant(std::numeric_limits<double>::infinity()), frustum_hi = -frustum_lo;
  for (const double t : {camera.near, far}) {
    const Vec3<double> c = to_view(camera.eye + t * forward);
    const double r = t * tan_diagonal;
    for (int axis = 0; axis < 2; ++axis) {
      const double extent = r * std::sqrt(std::max(0.0, 1.0 - forward_view[axis] * forward_view[axis]));
      frustum_lo[axis] = std::min(frustum_lo[axis], c[axis] - extent);
      frustum_hi[axis] = std::max(frustum_hi[axis], c[axis] + extent);
    }
  }
  double x0 = std::max(scene_lo.x(), frustum_lo.x()), x1 = std::min(scene_hi.x(), frustum_hi.x());
  double y0 = std::max(scene_lo.y(), frustum_lo.y()), y1 = std::min(scene_hi.y(), frustum_hi.y());
  if (!(x0 < x1 && y0 < y1)) {  // the camera sees none of the scene's box: the whole box
    x0 = scene_lo.x(), x1 = scene_hi.x(), y0 = scene_lo.y(), y1 = scene_hi.y();
  }
  // Depth along the light (positive away from it): −z right-handed, +z left-handed.
  const double axis_sign = conv.clip.hand == Handedness::Right ? -1.0 : 1.0;
  const double z_a = axis_sign * scene_lo.z(), z_b = axis_sign * scene_hi.z();
  const double depth_lo = std::min(z_a, z_b), depth_hi = std::max(z_a, z_b);

  LightFit fit;
  fit.size = map_size;
  LightView v;
  v.view = *view;
  if (sin_gamma < kLispsmMinSinGamma) {
    const double margin = kLispsmDepthMargin * (depth_hi - depth_lo) + 1e-6 * R;
    const Result<Mat4<double>> ortho = ortho_for<double>(conv, x0, x1, y0, y1, depth_lo - margin, depth_hi + margin);
    if (!ortho) return ortho.error();
    v.projection = *ortho;
    fit.views.push_back(std::move(v));
    return fit;
  }
  const double d = std::max(y1 - y0, 1e-9 * R);
  const double z_n = camera.near / sin_gamma;
  const double z_f = z_n + d * sin_gamma;
  const double n = (z_n + std::sqrt(z_n * z_f)) / sin_gamma;
  const double f = n + d;
  const double e_x = to_view(camera.eye).x();
  const double a = (f + n) / (f - n), b = -2.0 * f * n / (f - n);
  // W, acting on light-view (x, y, z, 1): rows give (x − e_x, a w + b, z, w) with w = y − y0 + n.
  Mat4<double> warp = Mat4<double>::Zero();
  warp(0, 0) = 1;
  warp(0, 3) = -e_x;
  warp(1, 1) = a;
  warp(1, 3) = a * (n - y0) + b;
  warp(2, 2) = 1;
  warp(3, 1) = 1;
  warp(3, 3) = n - y0;
  // W's image of the body: x / w and depth / w are extreme at the body's corners (w in [n, f]).
  double X0 = std::numeric_limits<double>::infinity(), X1 = -X0, D0 = X0, D1 = -X0;
  for (const double w : {n, f}) {
    for (const double x : {x0, x1}) {
      X0 = std::min(X0, (x - e_x) / w);
      X1 = std::max(X1, (x - e_x) / w);
    }
    for (const double depth : {depth_lo, depth_hi}) {
      D0 = std::min(D0, depth / w);
      D1 = std::max(D1, depth / w);
    }
  }
  const double margin = kLispsmDepthMargin * (D1 - D0) + 1e-12;
  // ortho_for takes distances along its viewing direction: W's image keeps light-view z's axis, so
  // the depth / w range is the range of distances in W's image.
  const Result<Mat4<double>> ortho = ortho_for<double>(conv, X0, X1, -1.0, 1.0, D0 - margin, D1 + margin);
  if (!ortho) return ortho.error();
  v.projection = *ortho * warp;
  fit.views.push_back(std::move(v));
  return fit;
}

}  // namespace shadowref
