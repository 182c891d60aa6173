// shadowref/stencil_count.hpp — the CPU stencil count: what the stencil buffer holds at a pixel,
// computed from the volume's geometry. The ground truth that ties the math to the picture.
//
// For an eye E and a visible surface point p, with the volume's triangles front-facing when seen
// counter-clockwise (volume.hpp: fronts face out of the volume):
//   * z-pass count = signed crossings of volume triangles on the open segment E -> p: +1 for a
//     triangle whose front faces E (the ray enters), −1 for a back face (it leaves). It equals
//     (volumes containing p) − (volumes containing E): right only while the eye is outside.
//   * z-fail count = signed crossings on the ray from p onward (away from E, up to and including
//     its point at infinity, where a dark cap at infinity lies): +1 for a back face, −1 for a
//     front face. It equals (volumes containing p) − (volumes containing the ray's end), and the
//     end is outside every capped volume: right wherever the eye is.
//   * containment_count(p) = the same count along a fixed direction: the winding number of a
//     closed (capped) volume at p; in_shadow(p) = containment_count(p) > 0.
//
// Exact-arithmetic formulation, so that triangles with vertices at infinity (w = 0) are handled
// like finite ones: a triangle is the cone {a V0 + b V1 + c V2 : a, b, c >= 0} in homogeneous 4D
// space, a segment or ray is {s A + t B : s, t >= 0}, and the hit test uses 4x4 determinants
// (Plücker-style orientation tests), computed in double (or T if wider). Ties: a crossing exactly
// through a triangle's edge is counted by both triangles, and E or p exactly on a triangle's plane
// counts nothing for that triangle; callers choose points away from the volume's edges and faces.
// Cost: O(volume triangles) per query, a handful of 4x4 determinants each: a test oracle, not a
// renderer.
#pragma once

#include <cstdint>
#include <type_traits>

#include <Eigen/LU>  // 4x4 determinants

#include "shadowref/volume.hpp"

namespace shadowref {
namespace stencil_detail {

template <class T>
using Wide = std::conditional_t<(sizeof(T) > sizeof(double)), T, double>;

template <class W>
W det4(const Vec4<W>& a, const Vec4<W>& b, const Vec4<W>& c, const Vec4<W>& d) {
  Mat4<W> m;
  m << a, b, c, d;
  return m.determinant();
}

enum class Span { Segment, Ray };  // Segment: both ends open; Ray: B at infinity, included

// Signed crossing of triangle (v0, v1, v2) by the span from A to B, or 0 for none. The sign is
// from A's side: +1 when A sees the triangle's front (Π·A < 0 with Π·X = det[V0, V1, V2, X]:
// for finite vertices Π·X = −n·(x − v0)), −1 when A sees its back.
template <class W>
int crossing(const Vec4<W>& v0, const Vec4<W>& v1, const Vec4<W>& v2, const Vec4<W>& a, const Vec4<W>& b, Span span) {
  Vec4<W> pi;
  for (int k = 0; k < 4; ++k) pi[k] = det4<W>(v0, v1, v2, Vec4<W>(Vec4<W>::Unit(k)));
  if (pi.isZero(W(0))) return 0;  // degenerate triangle
  const W pa = pi.dot(a), pb = pi.dot(b);
  if (pa == W(0)) return 0;  // A on the triangle's plane: edge-on, nothing rasterised
  if (span == Span::Segment && pb == W(0)) return 0;
  if ((pa > W(0)) == (pb > W(0)) && pb != W(0)) return 0;  // both ends on one side
  // X = s A + t B on the triangle's hyperplane with s, t >= 0.
  Vec4<W> x = pb * a - pa * b;
  if (pa > W(0)) x = -x;  // then pb <= 0: s = −pb, t = pa
  // X = α V0 + β V1 + γ V2 (Cramer with Π as the fourth column: det[V0, V1, V2, Π] = Π·Π > 0).
  const W alpha = det4(x, v1, v2, pi), beta = det4(v0, x, v2, pi), gamma = det4(v0, v1, x, pi);
  if (alpha < W(0) || beta < W(0) || gamma < W(0)) return 0;
  return pa < W(0) ? 1 : -1;
}

template <class T>
int signed_crossings(const ShadowVolume<T>& vol, const Vec3<T>& from, const Vec4<T>& to, Span span) {
  using W = Wide<T>;
  const Vec4<W> a(W(from.x()), W(from.y()), W(from.z()), W(1));
  const Vec4<W> b = to.template cast<W>();
  int sum = 0;
  for (std::size_t i = 0; i + 2 < vol.indices.size(); i += 3)
    sum += crossing<W>(vol.vertices[vol.indices[i]].template cast<W>(), vol.vertices[vol.indices[i + 1]].template cast<W>(),
                       vol.vertices[vol.indices[i + 2]].template cast<W>(), a, b, span);
  return sum;
}

}  // namespace stencil_detail

// The z-pass stencil count at surface point p seen from eye E: front faces crossed on E -> p
// minus back faces crossed (all triangles in `vol`, capped or not). See the top of this file.
template <class T>
int zpass_count(const ShadowVolume<T>& vol, const Vec3<T>& eye, const Vec3<T>& p) {
  return stencil_detail::signed_crossings(vol, eye, Vec4<T>(p.x(), p.y(), p.z(), T(1)), stencil_detail::Span::Segment);
}

// The z-fail stencil count at surface point p seen from eye E: back faces crossed beyond p (to
// infinity, inclusive) minus front faces crossed beyond p. Needs a capped volume.
template <class T>
int zfail_count(const ShadowVolume<T>& vol, const Vec3<T>& eye, const Vec3<T>& p) {
  const Vec3<T> d = p - eye;
  // From p, a crossing's sign from p's side is the opposite of the stencil operation's (a back
  // face seen from E is one p is behind: Π·p > 0 gives −1 there, and z-fail increments it).
  return -stencil_detail::signed_crossings(vol, p, Vec4<T>(d.x(), d.y(), d.z(), T(0)), stencil_detail::Span::Ray);
}

// The winding number of a closed (capped) volume at p: how many of its prisms contain p, counted
// along a fixed direction chosen off the axes and the diagonals so that the volumes of boxes and
// axis-aligned lights are not grazed. Precondition: a capped volume (or a directional light to
// infinity, whose sides close at one point).
template <class T>
int containment_count(const ShadowVolume<T>& vol, const Vec3<T>& p) {
  const Vec3<T> dir(T(0.2718281828), T(0.5772156649), T(-0.7071067812));
  return zfail_count(vol, Vec3<T>(p - dir), p);
}

// Whether p lies inside the shadow volume (containment_count > 0).
template <class T>
bool in_shadow(const ShadowVolume<T>& vol, const Vec3<T>& p) {
  return containment_count(vol, p) > 0;
}

}  // namespace shadowref
