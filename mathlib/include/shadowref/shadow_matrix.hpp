// shadowref/shadow_matrix.hpp — the planar projected-shadow matrix (D3DXMatrixShadow, XMMatrixShadow).
//
// Canonical (column vectors, v' = S v):   S = (P·L) I − L Pᵀ
// where P is the plane normalised by |(a, b, c)| and L the homogeneous light (w = 1 point light,
// w = 0 directional light with xyz pointing toward the light). S v lies on the plane for every v
// with P·v ≠ … (after the homogeneous divide), points on the plane stay put, and S L = 0.
// The D3DX layout (row vectors, v' = v S') is S' = Sᵀ, field by field the matrix that the classic
// CreateShadowMatrix listing builds: _11 = P·L − L.x a, _21 = −L.x b, …, _44 = P·L − L.w d.
//
// Degenerate input → Error: NonFinite (any NaN/inf), ZeroNormal (|(a,b,c)| = 0; old D3DX returned
// zeros, DirectXMath NaN), ZeroLight (L = 0), LightOnPlane (P·L is zero up to rounding: S would
// have rank 1 and flatten everything onto the line through L — no useful shadow exists).
// Points with (P·L)(P·v) < 0 after normalisation lie "beyond the light" and project to w < 0,
// which a GPU clips; that is the technique's behaviour, not an error here.
// Cost: one square root and 16 multiply-adds.
#pragma once

#include <cmath>
#include <limits>

#include "shadowref/conventions.hpp"
#include "shadowref/plane.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

// P·L is "zero up to rounding" when it is no larger than a few ulps of the sum of the magnitudes
// of its terms (the error bound of a 4-term dot product is 4 ε Σ|Pi Li|).
template <class T>
bool light_on_plane(const Plane<T>& normalised, const Vec4<T>& light) {
  const T pl = dot(normalised, light);
  const T scale = normalised.abcd.cwiseAbs().dot(light.cwiseAbs());
  return std::abs(pl) <= T(4) * std::numeric_limits<T>::epsilon() * scale;
}

// Canonical shadow matrix S = (P·L) I − L Pᵀ (column vectors). See the header comment.
template <class T>
Result<Mat4<T>> shadow_matrix(const Plane<T>& plane, const Vec4<T>& light) {
  if (!plane.abcd.allFinite() || !light.allFinite()) return Error::NonFinite;
  if ((light.array() == T(0)).all()) return Error::ZeroLight;
  const Result<Plane<T>> np = normalize(plane);
  if (!np) return np.error();
  const Plane<T>& p = *np;
  if (light_on_plane(p, light)) return Error::LightOnPlane;
  const T pl = dot(p, light);
  Mat4<T> s = -light * p.abcd.transpose();
  s.diagonal().array() += pl;
  return s;
}

// The same matrix in D3DX layout (row vectors): Sᵀ, so that M(i, j) is field _{i+1}{j+1}.
template <class T>
Result<Mat4<T>> shadow_matrix_d3dx(const Plane<T>& plane, const Vec4<T>& light) {
  Result<Mat4<T>> s = shadow_matrix(plane, light);
  if (!s) return s.error();
  return Mat4<T>(s->transpose());
}

}  // namespace shadowref
