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
// Cost: O(N) and O(1). Errors: NonFinite, NearNotPositive, FarNotBeyondNear,
// CascadeCountOutOfRange, SplitWeightOutOfRange, FovOutOfRange, ZeroAspect.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "shadowref/conventions.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

inline constexpr int kMaxCascades = 8;

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

}  // namespace shadowref
