// shadowref/volume_strategy.hpp — z-pass or z-fail, per caster: the near-plane clip volume test.
//
// z-pass counts volume faces between the near plane and the surface; it is wrong wherever the
// near rectangle itself lies inside a shadow volume (the count starts from the wrong value).
// A point q of the near rectangle lies in the caster's volume only if the segment from q to the
// light meets the caster, so the near rectangle is safe iff the caster misses the NEAR-PLANE CLIP
// VOLUME: the convex hull of the near rectangle and the light (for a directional light, the near
// rectangle swept toward the light to infinity). That is Lengyel's test ("Mathematics for 3D Game
// Programming and Computer Graphics", the near-plane clip volume), which works the same for a
// light in front of the near plane, behind it, or in it (the hull is then flat).
//
// The test here is a separating-axis test between that hull and the caster's bounding sphere on
// a fixed set of candidate axes (the near plane's normal, the planes through the light and each
// near-rectangle edge, the rectangle's edges and the light's directions within the near plane).
// Conservative by construction: "does not touch" is only answered when a separating plane was
// found, with a margin of a few ulps of the scene's scale; otherwise z-fail (always right, costs
// the caps) is chosen.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "shadowref/conventions.hpp"
#include "shadowref/mesh.hpp"
#include "shadowref/result.hpp"
#include "shadowref/silhouette.hpp"  // validate_light

namespace shadowref {

template <class T>
struct BoundingSphere {
  Vec3<T> center = Vec3<T>::Zero();
  T radius = T(0);
};

// A sphere containing every vertex a triangle uses: centre of their bounding box, radius the
// largest distance to it (not the smallest sphere; within a factor sqrt(3) of it). Errors: those of
// validate_mesh. Cost: O(T).
template <class T>
Result<BoundingSphere<T>> bounding_sphere(const TriangleMesh<T>& mesh) {
  if (const auto bad = validate_mesh(mesh)) return *bad;
  Vec3<T> lo = mesh.positions[mesh.triangles[0][0]], hi = lo;
  for (const auto& t : mesh.triangles)
    for (std::uint32_t v : t) {
      lo = lo.cwiseMin(mesh.positions[v]);
      hi = hi.cwiseMax(mesh.positions[v]);
    }
  BoundingSphere<T> s{(lo + hi) / T(2), T(0)};
  for (const auto& t : mesh.triangles)
    for (std::uint32_t v : t) s.radius = std::max(s.radius, (mesh.positions[v] - s.center).norm());
  if (!s.center.allFinite() || !std::isfinite(s.radius)) return Error::NonFinite;  // overflow
  return s;
}

// The near rectangle's corners in world space, from the camera's view-projection matrix (column
// vectors, clip = VP * world) and its clip convention: the clip-space points (x, y) = (−1, −1),
// (1, −1), (1, 1), (−1, 1) on the near plane (z = −1 for NegOneToOne, 0 for ZeroToOne, 1 reversed),
// unprojected. Errors: NonFinite, SingularMatrix (no inverse, or a corner at infinity). Works for
// finite and infinite projections. Cost: one 4x4 inverse.
template <class T>
Result<std::array<Vec3<T>, 4>> near_rectangle(const Mat4<T>& view_projection, ClipConvention conv = kOpenGL) {
  if (!view_projection.allFinite()) return Error::NonFinite;
  Mat4<T> inv;
  bool invertible = false;
  view_projection.computeInverseWithCheck(inv, invertible, T(0));
  if (!invertible || !inv.allFinite()) return Error::SingularMatrix;
  const T z = conv.order == DepthOrder::Reversed ? T(1) : conv.depth == DepthRange::NegOneToOne ? T(-1) : T(0);
  const T xs[4] = {-1, 1, 1, -1}, ys[4] = {-1, -1, 1, 1};
  std::array<Vec3<T>, 4> corners;
  for (int i = 0; i < 4; ++i) {
    const Vec4<T> h = inv * Vec4<T>(xs[i], ys[i], z, T(1));
    if (!(h.w() != T(0))) return Error::SingularMatrix;
    corners[i] = h.template head<3>() / h.w();
    if (!corners[i].allFinite()) return Error::SingularMatrix;
  }
  return corners;
}

enum class StencilMethod {
  ZPass,  // sides only, count from the near plane: safe, the caster misses the near clip volume
  ZFail,  // sides and both caps, count from infinity (Carmack's reverse): always right
};

inline constexpr const char* to_string(StencilMethod m) { return m == StencilMethod::ZPass ? "z-pass" : "z-fail"; }

// Whether the caster's bounding sphere may touch the near-plane clip volume of `near` (corners in
// order around the rectangle) and the homogeneous light. true = may touch (use z-fail); false =
// provably disjoint (z-pass is safe). Ties and rounding count as touching: the separation must
// exceed 64 ulps of the largest coordinate involved (why 64: the support values are sums of three
// products of rounded inputs, a few ulps each; 64 keeps a wide margin and is still far below any
// scene's feature size). Errors: those of validate_light; NonFinite for a non-finite corner or
// sphere, or a negative radius. Cost: 13 candidate axes, O(1).
template <class T>
Result<bool> near_clip_volume_touches(const std::array<Vec3<T>, 4>& near, const Vec4<T>& light,
                                      const BoundingSphere<T>& caster) {
  if (const auto bad = validate_light(light)) return *bad;
  for (const auto& c : near)
    if (!c.allFinite()) return Error::NonFinite;
  if (!caster.center.allFinite() || !std::isfinite(caster.radius) || caster.radius < T(0)) return Error::NonFinite;

  const bool directional = light.w() == T(0);
  const Vec3<T> lp = directional ? Vec3<T>(light.template head<3>()) : Vec3<T>(light.template head<3>() / light.w());
  if (!lp.allFinite()) return Error::NonFinite;
  // Scale of the problem, for the rounding margin.
  T scale = caster.center.cwiseAbs().maxCoeff() + caster.radius;
  for (const auto& c : near) scale = std::max(scale, c.cwiseAbs().maxCoeff());
  if (!directional) scale = std::max(scale, lp.cwiseAbs().maxCoeff());
  const T slack_per_unit_axis = T(64) * std::numeric_limits<T>::epsilon() * scale;

  // True when `axis` separates the hull from the sphere.
  const auto separates = [&](const Vec3<T>& axis) {
    const T len = axis.norm();
    if (!(len > T(0)) || !std::isfinite(len)) return false;  // degenerate axis: no verdict
    T lo = std::numeric_limits<T>::infinity(), hi = -lo;
    for (const auto& c : near) {
      lo = std::min(lo, axis.dot(c));
      hi = std::max(hi, axis.dot(c));
    }
    if (directional) {  // rays from the corners toward the light, to infinity
      const T s = axis.dot(lp);
      if (s > T(0)) hi = std::numeric_limits<T>::infinity();
      if (s < T(0)) lo = -std::numeric_limits<T>::infinity();
    } else {
      lo = std::min(lo, axis.dot(lp));
      hi = std::max(hi, axis.dot(lp));
    }
    const T c = axis.dot(caster.center), r = caster.radius * len, slack = slack_per_unit_axis * len;
    return c + r < lo - slack || c - r > hi + slack;
  };

  const Vec3<T> nn = (near[1] - near[0]).cross(near[3] - near[0]);
  if (separates(nn)) return false;
  for (int i = 0; i < 4; ++i) {
    const Vec3<T> edge = near[(i + 1) % 4] - near[i];
    const Vec3<T> to_light = directional ? lp : Vec3<T>(lp - near[i]);
    if (separates(edge.cross(to_light))) return false;  // plane through the light and the edge
    if (separates(nn.cross(edge))) return false;        // the rectangle's own side, in its plane
    if (separates(nn.cross(to_light))) return false;    // hull edge corner -> light, seen in the plane
  }
  return true;
}

// z-pass where near_clip_volume_touches says the caster cannot touch the near clip volume,
// z-fail elsewhere. Errors: those of near_clip_volume_touches.
template <class T>
Result<StencilMethod> choose_stencil_method(const std::array<Vec3<T>, 4>& near, const Vec4<T>& light,
                                            const BoundingSphere<T>& caster) {
  const auto touches = near_clip_volume_touches(near, light, caster);
  if (!touches) return touches.error();
  return *touches ? StencilMethod::ZFail : StencilMethod::ZPass;
}

}  // namespace shadowref
