// shadowref/plane.hpp — planes (a, b, c, d): a x + b y + c z + d = 0.
//
// The normal is (a, b, c); it need not be unit length unless a function says so. Normalising
// divides all four coefficients by |(a, b, c)| (D3DXPlaneNormalize). Construction validates its
// input and returns a Result: a zero-length normal, collinear points or a NaN/infinite value is an
// Error, never a plane full of NaN. The dot products are plain arithmetic (O(1), no checks): they
// are the inner loops of everything else.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Geometry>  // cross products

#include "shadowref/conventions.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

template <class T>
struct Plane {
  Vec4<T> abcd = Vec4<T>::Zero();  // (a, b, c, d)

  T a() const { return abcd[0]; }
  T b() const { return abcd[1]; }
  T c() const { return abcd[2]; }
  T d() const { return abcd[3]; }
  Vec3<T> normal() const { return abcd.template head<3>(); }
};

// A plane from its coefficients, unnormalised. Errors: NonFinite, ZeroNormal.
template <class T>
Result<Plane<T>> plane_from_coefficients(T a, T b, T c, T d) {
  Plane<T> p{Vec4<T>(a, b, c, d)};
  if (!p.abcd.allFinite()) return Error::NonFinite;
  if (p.normal().squaredNorm() == T(0)) return Error::ZeroNormal;
  return p;
}

// The plane through `point` with normal `normal` (any non-zero length, kept as given):
// (n.x, n.y, n.z, -n·point). Errors: NonFinite, ZeroNormal.
template <class T>
Result<Plane<T>> plane_from_point_normal(const Vec3<T>& point, const Vec3<T>& normal) {
  if (!point.allFinite() || !normal.allFinite()) return Error::NonFinite;
  if (normal.squaredNorm() == T(0)) return Error::ZeroNormal;
  Plane<T> p{Vec4<T>(normal.x(), normal.y(), normal.z(), -normal.dot(point))};
  if (!p.abcd.allFinite()) return Error::NonFinite;  // overflow of the dot product
  return p;
}

// The plane through three points, normal = (p1 - p0) × (p2 - p0), unnormalised (as
// D3DXPlaneFromPoints: counter-clockwise points seen from the front, in a right-handed frame).
// Errors: NonFinite, CollinearPoints (the cross product is exactly zero or underflows to zero).
template <class T>
Result<Plane<T>> plane_from_points(const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2) {
  if (!p0.allFinite() || !p1.allFinite() || !p2.allFinite()) return Error::NonFinite;
  const Vec3<T> n = (p1 - p0).cross(p2 - p0);
  if (!n.allFinite()) return Error::NonFinite;
  if (n.squaredNorm() == T(0)) return Error::CollinearPoints;
  return Plane<T>{Vec4<T>(n.x(), n.y(), n.z(), -n.dot(p0))};
}

// The plane divided by |(a, b, c)|, so that dot_coord gives the signed distance.
// Errors: NonFinite, ZeroNormal. Cost: one square root.
template <class T>
Result<Plane<T>> normalize(const Plane<T>& p) {
  if (!p.abcd.allFinite()) return Error::NonFinite;
  const Vec3<T> n = p.normal();
  if ((n.array() == T(0)).all()) return Error::ZeroNormal;
  // The plain sqrt(a²+b²+c²) is what D3DX computes; only when its square overflows or underflows
  // do we pay for Eigen's scaled stableNorm().
  T len = n.norm();
  if (!(len > T(0)) || !std::isfinite(len)) len = n.stableNorm();
  Plane<T> q{p.abcd / len};
  if (!q.abcd.allFinite()) return Error::NonFinite;
  return q;
}

// a px + b py + c pz + d (D3DXPlaneDotCoord): the point's side of the plane, scaled by |n|.
template <class T>
T dot_coord(const Plane<T>& p, const Vec3<T>& point) {
  return p.normal().dot(point) + p.d();
}

// a vx + b vy + c vz (D3DXPlaneDotNormal): the plane's normal against a direction.
template <class T>
T dot_normal(const Plane<T>& p, const Vec3<T>& v) {
  return p.normal().dot(v);
}

// The full 4D dot product a x + b y + c z + d w (D3DXPlaneDot) against a homogeneous point.
template <class T>
T dot(const Plane<T>& p, const Vec4<T>& v) {
  return p.abcd.dot(v);
}

// The signed Euclidean distance from the plane to `point` (positive on the normal's side),
// whatever the length of the normal. Precondition: a valid plane (non-zero normal).
template <class T>
T signed_distance(const Plane<T>& p, const Vec3<T>& point) {
  return dot_coord(p, point) / p.normal().norm();
}

}  // namespace shadowref
