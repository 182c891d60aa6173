// shadowref_adapter.hpp — the math adapter for shadowref's own mathlib (the reference
// implementation). teeth_test.cpp starts from it to build the deliberately wrong variants.
#pragma once

#include "math_adapter.hpp"
#include "shadowref/plane.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/shadow_matrix.hpp"

namespace shadowref::prop {

template <class T>
MathFunctions<T> shadowref_math_functions() {
  using M = typename MathFunctions<T>::Matrix;
  const auto unwrap = [](const Result<Mat4<T>>& r) -> M { return r ? M(*r) : std::nullopt; };
  MathFunctions<T> f;
  f.shadow_matrix = [unwrap](const Vec4<T>& p, const Vec4<T>& l) { return unwrap(shadow_matrix(Plane<T>{p}, l)); };
  f.shadow_matrix_d3dx = [unwrap](const Vec4<T>& p, const Vec4<T>& l) {
    return unwrap(shadow_matrix_d3dx(Plane<T>{p}, l));
  };
  f.perspective = [unwrap](T fovy, T aspect, T near, T far, ClipConvention c) {
    return unwrap(perspective(fovy, aspect, near, far, c));
  };
  f.perspective_infinite = [unwrap](T fovy, T aspect, T near, T eps, ClipConvention c) {
    return unwrap(perspective_infinite(fovy, aspect, near, c, eps));
  };
  f.frustum = [unwrap](T l, T r, T b, T t, T near, T far, ClipConvention c) {
    return unwrap(frustum(l, r, b, t, near, far, c));
  };
  f.ortho = [unwrap](T l, T r, T b, T t, T near, T far, ClipConvention c) {
    return unwrap(ortho(l, r, b, t, near, far, c));
  };
  f.finite_conventions = all_conventions();
  f.infinite_conventions = all_conventions();
  f.frustum_conventions = all_conventions();
  f.ortho_conventions = all_conventions();
  return f;
}

inline MathAdapter shadowref_math_adapter() {
  return {"shadowref mathlib", shadowref_math_functions<float>(), shadowref_math_functions<double>()};
}

}  // namespace shadowref::prop
