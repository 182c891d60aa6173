// shadowref/glm_interop.hpp — conversions between shadowref's Eigen matrices and GLM.
//
// Opt-in (the core needs only Eigen): include this header and link glm::glm. GLM is column-major
// with column vectors, like the canonical form: glm_m[c][r] == M(r, c). No failure mode.
#pragma once

#include <glm/glm.hpp>

#include "shadowref/conventions.hpp"

namespace shadowref {

template <class T>
glm::mat<4, 4, T, glm::defaultp> to_glm(const Mat4<T>& m) {
  glm::mat<4, 4, T, glm::defaultp> g(T(0));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) g[c][r] = m(r, c);
  return g;
}

template <class T>
Mat4<T> from_glm(const glm::mat<4, 4, T, glm::defaultp>& g) {
  Mat4<T> m;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m(r, c) = g[c][r];
  return m;
}

template <class T>
glm::vec<4, T, glm::defaultp> to_glm(const Vec4<T>& v) {
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace shadowref
