// shadowref/conventions.hpp — the conventions every header of the math core follows.
//
//   * Canonical form: COLUMN vectors, v' = M * v (OpenGL, GLM, Eigen). Storage order is Eigen's
//     default (column-major); it never matters to callers, who index M(row, col).
//   * D3DX layout: ROW vectors, v' = v * M, fields _11 … _44 row by row. It is the transpose of
//     the canonical matrix (see d3dx.hpp). Functions that return a D3DX-layout matrix say "_d3dx".
//   * Planes (a, b, c, d): a x + b y + c z + d = 0 (see plane.hpp).
//   * Lights are homogeneous points L = (x, y, z, w): w = 1 a point light at xyz, w = 0 a
//     directional light whose xyz points from the scene TOWARD the light.
//   * Depth ranges: NegOneToOne (OpenGL clip space) and ZeroToOne (Direct3D, Vulkan), and
//     reversed-Z (near -> 1, far -> 0) on top of ZeroToOne.
//   * Handedness: Right (view space looks down -z, OpenGL/GLM default) and Left (looks down +z,
//     Direct3D/DirectXMath default).
//
// Every function is templated on the scalar (float, double, long double) and never returns a
// silent NaN: functions that can fail return a Result (result.hpp) that says why.
#pragma once

#include <Eigen/Core>

namespace shadowref {

template <class T> using Vec2 = Eigen::Matrix<T, 2, 1>;
template <class T> using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T> using Vec4 = Eigen::Matrix<T, 4, 1>;
template <class T> using Mat3 = Eigen::Matrix<T, 3, 3>;
template <class T> using Mat4 = Eigen::Matrix<T, 4, 4>;

// Which clip-space z range a projection maps [near, far] onto.
enum class DepthRange {
  NegOneToOne,  // OpenGL: near -> -1, far -> +1
  ZeroToOne,    // Direct3D, Vulkan: near -> 0, far -> 1
};

// Which way the view space looks.
enum class Handedness {
  Right,  // looks down -z (OpenGL, GLM's *RH*)
  Left,   // looks down +z (Direct3D, GLM's *LH*)
};

// Depth direction. Reversed-Z is only defined with DepthRange::ZeroToOne: near -> 1, far -> 0.
enum class DepthOrder { Standard, Reversed };

// The convention a projection is built in. Defaults: RH, -1..1, standard depth (OpenGL).
struct ClipConvention {
  Handedness hand = Handedness::Right;
  DepthRange depth = DepthRange::NegOneToOne;
  DepthOrder order = DepthOrder::Standard;
};

inline constexpr ClipConvention kOpenGL{Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Standard};
inline constexpr ClipConvention kDirect3D{Handedness::Left, DepthRange::ZeroToOne, DepthOrder::Standard};

inline constexpr const char* to_string(DepthRange r) {
  return r == DepthRange::NegOneToOne ? "neg-one-to-one" : "zero-to-one";
}
inline constexpr const char* to_string(Handedness h) { return h == Handedness::Right ? "rh" : "lh"; }
inline constexpr const char* to_string(DepthOrder o) {
  return o == DepthOrder::Standard ? "standard" : "reversed";
}

}  // namespace shadowref
