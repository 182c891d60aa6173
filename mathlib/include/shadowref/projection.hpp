// shadowref/projection.hpp — perspective and orthographic projections in every convention.
//
// All matrices are canonical (column vectors, clip = M * view). `ClipConvention` picks
// handedness (RH looks down −z, LH down +z), depth range (−1..1 or 0..1) and depth order
// (reversed-Z: near → 1, far → 0, only with 0..1). For D3DX layout, transpose (d3dx.hpp).
//
// With s = −1 for RH and +1 for LH (the sign of view-space z in front of the eye), the finite
// perspective's last two rows are
//     −1..1:  (0, 0, s (f+n)/(f−n), −2 f n/(f−n)),  (0, 0, s, 0)
//      0..1:  (0, 0, s f/(f−n),        −f n/(f−n)),  (0, 0, s, 0)
// which equal GLM 0.9.9.8's perspective{RH,LH}_{NO,ZO} term by term (same expression order, so
// float results are bit-identical). The infinite forms are the limit f → ∞:
//     −1..1:  (0, 0, s (1−ε), (ε−2) n)        0..1:  (0, 0, s (1−ε), (ε−1) n)
// where ε ≥ 0 is Lengyel's tweak: with ε > 0, directions (w = 0) map strictly inside the far
// plane, so extruded shadow-volume vertices survive rounding. (GLM's tweakedInfinitePerspective
// defaults to ε = 2^-23, which is too small in float; `kSafeInfiniteEpsilonFloat` is safe.)
// Reversed-Z is R · M with R = rows (1,0,0,0), (0,1,0,0), (0,0,−1,1), (0,0,0,1): depth' = 1 − depth;
// its infinite form's third row is (0, 0, 0, n) for RH.
//
// Errors: NonFinite, NearNotPositive, FarNotBeyondNear, ZeroAspect, FovOutOfRange, EmptyFrustum,
// EpsilonOutOfRange, ReversedNeedsZeroToOne. Cost: one tangent, a few divisions.
#pragma once

#include <cmath>
#include <numbers>
#include <optional>

#include "shadowref/conventions.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

// An epsilon that keeps w = 0 directions strictly inside the far plane when P · V is applied in
// float. Measured (projection_test, GlmsDefaultTweakEpsilonIsTooSmallInFloat: random views with
// translations up to 50, 10^5 in-frustum directions): 2^-23 (GLM's default) lets some directions
// land beyond the far plane (clipped); 2.4e-7 clips none but leaves some exactly ON it (depth 1);
// 4.8e-7 keeps all strictly inside. Its cost: the depth range loses 4.8e-7 of its extent.
inline constexpr double kSafeInfiniteEpsilonFloat = 4.8e-7;

namespace detail {

template <class T>
T view_sign(Handedness h) {
  return h == Handedness::Right ? T(-1) : T(1);
}

template <class T>
Mat4<T> reverse_depth(const Mat4<T>& m) {
  Mat4<T> r = m;
  r.row(2) = m.row(3) - m.row(2);
  return r;
}

template <class T>
Result<Mat4<T>> finish(const Mat4<T>& m, const ClipConvention& conv) {
  Mat4<T> out = conv.order == DepthOrder::Reversed ? reverse_depth(m) : m;
  if (!out.allFinite()) return Error::NonFinite;  // overflow of extreme inputs
  return out;
}

inline std::optional<Error> check_convention(const ClipConvention& conv) {
  if (conv.order == DepthOrder::Reversed && conv.depth != DepthRange::ZeroToOne)
    return Error::ReversedNeedsZeroToOne;
  return std::nullopt;
}

// The depth rows (third and fourth) of a finite perspective, in GLM's expression order.
template <class T>
void finite_depth_rows(Mat4<T>& m, T s, T near, T far, DepthRange depth) {
  m(3, 2) = s;
  if (depth == DepthRange::NegOneToOne) {
    m(2, 2) = s * (far + near) / (far - near);
    m(2, 3) = -(T(2) * far * near) / (far - near);
  } else {
    m(2, 2) = s * far / (far - near);
    m(2, 3) = -(far * near) / (far - near);
  }
}

// The depth rows of the infinite form (the limit far → ∞) with Lengyel's epsilon.
template <class T>
void infinite_depth_rows(Mat4<T>& m, T s, T near, T epsilon, DepthRange depth) {
  m(3, 2) = s;
  m(2, 2) = s * (T(1) - epsilon);
  m(2, 3) = depth == DepthRange::NegOneToOne ? (epsilon - T(2)) * near : (epsilon - T(1)) * near;
}

}  // namespace detail

// Finite perspective from the vertical field of view (radians), aspect = width / height,
// 0 < near < far. Equals GLM's perspective{RH,LH}_{NO,ZO}.
template <class T>
Result<Mat4<T>> perspective(T fovy, T aspect, T near, T far, ClipConvention conv = {}) {
  using std::tan, std::isfinite;
  if (auto e = detail::check_convention(conv)) return *e;
  if (!isfinite(fovy) || !isfinite(aspect) || !isfinite(near) || !isfinite(far)) return Error::NonFinite;
  if (!(fovy > T(0) && fovy < std::numbers::pi_v<T>)) return Error::FovOutOfRange;
  if (!(aspect > T(0))) return Error::ZeroAspect;
  if (!(near > T(0))) return Error::NearNotPositive;
  if (!(far > near)) return Error::FarNotBeyondNear;
  const T s = detail::view_sign<T>(conv.hand);
  const T tan_half = tan(fovy / T(2));
  Mat4<T> m = Mat4<T>::Zero();
  m(0, 0) = T(1) / (aspect * tan_half);
  m(1, 1) = T(1) / tan_half;
  detail::finite_depth_rows(m, s, near, far, conv.depth);
  return detail::finish(m, conv);
}

// Infinite perspective (far plane at infinity), optional epsilon in [0, 1) (Lengyel's tweak).
template <class T>
Result<Mat4<T>> perspective_infinite(T fovy, T aspect, T near, ClipConvention conv = {}, T epsilon = T(0)) {
  using std::tan, std::isfinite;
  if (auto e = detail::check_convention(conv)) return *e;
  if (!isfinite(fovy) || !isfinite(aspect) || !isfinite(near) || !isfinite(epsilon)) return Error::NonFinite;
  if (!(fovy > T(0) && fovy < std::numbers::pi_v<T>)) return Error::FovOutOfRange;
  if (!(aspect > T(0))) return Error::ZeroAspect;
  if (!(near > T(0))) return Error::NearNotPositive;
  if (!(epsilon >= T(0) && epsilon < T(1))) return Error::EpsilonOutOfRange;
  const T s = detail::view_sign<T>(conv.hand);
  const T tan_half = tan(fovy / T(2));
  Mat4<T> m = Mat4<T>::Zero();
  m(0, 0) = T(1) / (aspect * tan_half);
  m(1, 1) = T(1) / tan_half;
  detail::infinite_depth_rows(m, s, near, epsilon, conv.depth);
  return detail::finish(m, conv);
}

// Off-centre finite perspective from the near-plane rectangle [l, r] × [b, t] at distance n.
// Equals GLM's frustum{RH,LH}_{NO,ZO}.
template <class T>
Result<Mat4<T>> frustum(T l, T r, T b, T t, T near, T far, ClipConvention conv = {}) {
  using std::isfinite;
  if (auto e = detail::check_convention(conv)) return *e;
  if (!isfinite(l) || !isfinite(r) || !isfinite(b) || !isfinite(t) || !isfinite(near) || !isfinite(far))
    return Error::NonFinite;
  if (l == r || b == t) return Error::EmptyFrustum;
  if (!(near > T(0))) return Error::NearNotPositive;
  if (!(far > near)) return Error::FarNotBeyondNear;
  const T s = detail::view_sign<T>(conv.hand);
  Mat4<T> m = Mat4<T>::Zero();
  m(0, 0) = (T(2) * near) / (r - l);
  m(1, 1) = (T(2) * near) / (t - b);
  m(0, 2) = -s * (r + l) / (r - l);
  m(1, 2) = -s * (t + b) / (t - b);
  detail::finite_depth_rows(m, s, near, far, conv.depth);
  return detail::finish(m, conv);
}

// Off-centre infinite perspective (the frustum's limit for far → ∞), optional epsilon.
template <class T>
Result<Mat4<T>> frustum_infinite(T l, T r, T b, T t, T near, ClipConvention conv = {}, T epsilon = T(0)) {
  using std::isfinite;
  if (auto e = detail::check_convention(conv)) return *e;
  if (!isfinite(l) || !isfinite(r) || !isfinite(b) || !isfinite(t) || !isfinite(near) || !isfinite(epsilon))
    return Error::NonFinite;
  if (l == r || b == t) return Error::EmptyFrustum;
  if (!(near > T(0))) return Error::NearNotPositive;
  if (!(epsilon >= T(0) && epsilon < T(1))) return Error::EpsilonOutOfRange;
  const T s = detail::view_sign<T>(conv.hand);
  Mat4<T> m = Mat4<T>::Zero();
  m(0, 0) = (T(2) * near) / (r - l);
  m(1, 1) = (T(2) * near) / (t - b);
  m(0, 2) = -s * (r + l) / (r - l);
  m(1, 2) = -s * (t + b) / (t - b);
  detail::infinite_depth_rows(m, s, near, epsilon, conv.depth);
  return detail::finish(m, conv);
}

// Orthographic projection of the box [l, r] × [b, t] × [near, far] (near may be ≤ 0 here; only
// near ≠ far is needed). Equals GLM's ortho{RH,LH}_{NO,ZO}. Used for directional-light shadow maps.
template <class T>
Result<Mat4<T>> ortho(T l, T r, T b, T t, T near, T far, ClipConvention conv = {}) {
  using std::isfinite;
  if (auto e = detail::check_convention(conv)) return *e;
  if (!isfinite(l) || !isfinite(r) || !isfinite(b) || !isfinite(t) || !isfinite(near) || !isfinite(far))
    return Error::NonFinite;
  if (l == r || b == t) return Error::EmptyFrustum;
  if (!(far > near)) return Error::FarNotBeyondNear;
  const T s = detail::view_sign<T>(conv.hand);
  Mat4<T> m = Mat4<T>::Identity();
  m(0, 0) = T(2) / (r - l);
  m(1, 1) = T(2) / (t - b);
  m(0, 3) = -(r + l) / (r - l);
  m(1, 3) = -(t + b) / (t - b);
  if (conv.depth == DepthRange::NegOneToOne) {
    m(2, 2) = s * T(2) / (far - near);
    m(2, 3) = -(far + near) / (far - near);
  } else {
    m(2, 2) = s * T(1) / (far - near);
    m(2, 3) = -near / (far - near);
  }
  return detail::finish(m, conv);
}

}  // namespace shadowref
