// shadowref/view.hpp — view matrices (world → view space), canonical column-vector form.
//
// look_at(eye, target, up, hand) equals GLM's lookAtRH / lookAtLH: the rows are the camera basis
// (side, up, ±forward) and the translation moves the eye to the origin. RH: the camera looks down
// −z of view space; LH: down +z. Errors: NonFinite, EyeAtTarget, UpParallelToView (the cross
// product of forward and up is zero or below rounding of its inputs). Cost: two square roots.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Geometry>  // cross products

#include "shadowref/conventions.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

template <class T>
Result<Mat4<T>> look_at(const Vec3<T>& eye, const Vec3<T>& target, const Vec3<T>& up,
                        Handedness hand = Handedness::Right) {
  if (!eye.allFinite() || !target.allFinite() || !up.allFinite()) return Error::NonFinite;
  const Vec3<T> dir = target - eye;
  if (dir.squaredNorm() == T(0)) return Error::EyeAtTarget;
  const Vec3<T> f = dir.normalized();
  const T up_len = up.norm();
  if (!(up_len > T(0))) return Error::UpParallelToView;
  // |f × up| = |up| sin(angle); below a few ulps of |up| the side vector is rounding noise.
  const Vec3<T> side = hand == Handedness::Right ? f.cross(up) : up.cross(f);
  if (!(side.norm() > T(8) * std::numeric_limits<T>::epsilon() * up_len)) return Error::UpParallelToView;
  const Vec3<T> s = side.normalized();
  const Vec3<T> u = hand == Handedness::Right ? s.cross(f) : f.cross(s);
  const Vec3<T> fwd = hand == Handedness::Right ? Vec3<T>(-f) : f;
  Mat4<T> m = Mat4<T>::Identity();
  m.template block<1, 3>(0, 0) = s.transpose();
  m.template block<1, 3>(1, 0) = u.transpose();
  m.template block<1, 3>(2, 0) = fwd.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = -fwd.dot(eye);
  if (!m.allFinite()) return Error::NonFinite;
  return m;
}

}  // namespace shadowref
