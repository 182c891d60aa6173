// math_adapter.hpp — the small interface the math properties are written against.
//
// An adapter gathers the functions under test: the planar shadow matrix in canonical (column-vector)
// and D3DX (row-vector) layout, the finite and infinite perspective projections, and (optionally)
// the off-centre frustum and the orthographic projection, in float and in double. shadowref's own
// mathlib is one adapter (adapters/shadowref_adapter.cpp), a GLM-style engine another
// (adapters/glm_adapter.cpp), and every deliberately wrong variant of teeth_test.cpp a third kind:
// the very same property code runs on all of them.
//
// To run the properties on your engine: write one source file that defines
// `shadowref::prop::math_adapter_under_test()` (copy adapters/glm_adapter.cpp) and add one CMake
// line, `shadowref_add_math_properties(my_engine adapters/my_engine_adapter.cpp [LIBRARIES ...])`.
//
// Conventions the adapter must translate to (see mathlib/include/shadowref/conventions.hpp):
//   * matrices are returned as Eigen 4x4 in the layout the function names: canonical = column
//     vectors (v' = M v, OpenGL/GLM), d3dx = row vectors (v' = v M, field _rc at (r-1, c-1));
//   * a plane (a, b, c, d) means a x + b y + c z + d = 0, passed UNNORMALISED: normalising it by
//     |(a, b, c)| is part of the contract under test (D3DXMatrixShadow does it);
//   * a light is homogeneous (x, y, z, w): w = 1 point light, w = 0 directional light toward xyz;
//   * the shadow matrix contract is S = (P·L) I − L Pᵀ with P normalised;
//   * projections follow the view space of their handedness (RH looks down −z, LH down +z) and
//     map the view volume onto the NDC square: x right, y up, in both handednesses;
//   * return std::nullopt when the implementation refuses the input (shadowref refuses a light
//     on the plane) or does not support a convention listed below as unsupported.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shadowref/conventions.hpp"

namespace shadowref::prop {

template <class T>
struct MathFunctions {
  using Matrix = std::optional<Mat4<T>>;
  // Canonical (column-vector) shadow matrix of the plane (a, b, c, d) and the homogeneous light.
  std::function<Matrix(const Vec4<T>& plane, const Vec4<T>& light)> shadow_matrix;
  // The same in D3DX layout (row vectors): D3DXMatrixShadow's output, field by field.
  std::function<Matrix(const Vec4<T>& plane, const Vec4<T>& light)> shadow_matrix_d3dx;
  // Finite perspective (canonical), vertical fov in radians, aspect = width / height.
  std::function<Matrix(T fovy, T aspect, T near, T far, ClipConvention conv)> perspective;
  // Infinite perspective (canonical) with Lengyel's epsilon (0 = the exact limit).
  std::function<Matrix(T fovy, T aspect, T near, T epsilon, ClipConvention conv)> perspective_infinite;
  // Off-centre finite perspective (canonical) from the near rectangle [l, r] × [b, t] at distance
  // near (glFrustum's arguments, in view-space x and y for both handednesses). Optional.
  std::function<Matrix(T l, T r, T b, T t, T near, T far, ClipConvention conv)> frustum;
  // Orthographic projection (canonical) of the box [l, r] × [b, t], near..far in front of the eye
  // (glOrtho's arguments; near may be ≤ 0). Optional.
  std::function<Matrix(T l, T r, T b, T t, T near, T far, ClipConvention conv)> ortho;
  // The conventions the projections support; properties only ask for these. An empty list for
  // frustum or ortho means the adapter does not have it: the properties of that projection are
  // skipped (and say so).
  std::vector<ClipConvention> finite_conventions;
  std::vector<ClipConvention> infinite_conventions;
  std::vector<ClipConvention> frustum_conventions;
  std::vector<ClipConvention> ortho_conventions;
};

struct MathAdapter {
  std::string name;
  MathFunctions<float> f32;
  MathFunctions<double> f64;

  template <class T>
  const MathFunctions<T>& get() const {
    if constexpr (std::is_same_v<T, float>) return f32;
    else return f64;
  }
};

// Every convention shadowref knows (a complete implementation supports all six).
inline std::vector<ClipConvention> all_conventions() {
  return {{Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Standard},
          {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Standard},
          {Handedness::Left, DepthRange::NegOneToOne, DepthOrder::Standard},
          {Handedness::Left, DepthRange::ZeroToOne, DepthOrder::Standard},
          {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Reversed},
          {Handedness::Left, DepthRange::ZeroToOne, DepthOrder::Reversed}};
}

// Defined by the adapter source that shadowref_add_math_properties() compiles in.
const MathAdapter& math_adapter_under_test();

}  // namespace shadowref::prop
