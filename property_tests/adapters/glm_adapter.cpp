// glm_adapter.cpp — the example adapter: the math properties run on a GLM-style engine.
//
// This is the one file an engine team writes (see README.md): it translates the engine's own shadow
// matrix and projections into the interface of math_adapter.hpp. Here the "engine" is plain GLM
// 0.9.9.8 plus a shadow matrix written the way GLM code usually writes it (column-major mat4, built
// column by column), so the properties check code that shares nothing with shadowref's mathlib.
// GLM has no reversed-Z and no 0..1 infinite projection, and its tweaked (epsilon) infinite
// projection is right-handed −1..1 only: the convention lists below say so, and the properties
// only ask for those. Its left-handed frustum is left out on purpose: GLM 0.9.9.8's frustumLH_*
// keep the right-handed sign of (r+l)/(r−l) and (t+b)/(t−b), so an off-centre LH frustum lands
// beside the NDC square (teeth_test.cpp shows the frustum property catching exactly that).
#define GLM_FORCE_SILENT_WARNINGS
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/glm.hpp>

#include "math_adapter.hpp"
#include "shadowref/glm_interop.hpp"

namespace shadowref::prop {
namespace {

using Conv = ClipConvention;

// The engine's shadow matrix: S = (P·L) I − L Pᵀ, P normalised by |(a, b, c)|. GLM indexes m[col][row].
template <class T>
glm::mat<4, 4, T> engine_shadow_matrix(glm::vec<4, T> plane, glm::vec<4, T> light) {
  const T len = glm::length(glm::vec<3, T>(plane));
  plane /= len;
  const T d = glm::dot(plane, light);
  glm::mat<4, 4, T> s(T(0));
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) s[col][row] = (row == col ? d : T(0)) - light[row] * plane[col];
  return s;
}

template <class T>
std::optional<glm::mat<4, 4, T>> engine_perspective(T fovy, T aspect, T near, T far, Conv c) {
  const bool rh = c.hand == Handedness::Right, no = c.depth == DepthRange::NegOneToOne;
  if (c.order != DepthOrder::Standard) return std::nullopt;
  if (rh) return no ? glm::perspectiveRH_NO(fovy, aspect, near, far) : glm::perspectiveRH_ZO(fovy, aspect, near, far);
  return no ? glm::perspectiveLH_NO(fovy, aspect, near, far) : glm::perspectiveLH_ZO(fovy, aspect, near, far);
}

template <class T>
std::optional<glm::mat<4, 4, T>> engine_perspective_infinite(T fovy, T aspect, T near, T epsilon, Conv c) {
  if (c.hand != Handedness::Right || c.depth != DepthRange::NegOneToOne || c.order != DepthOrder::Standard)
    return std::nullopt;
  return glm::tweakedInfinitePerspective(fovy, aspect, near, epsilon);
}

template <class T>
std::optional<glm::mat<4, 4, T>> engine_frustum(T l, T r, T b, T t, T near, T far, Conv c) {
  if (c.hand != Handedness::Right || c.order != DepthOrder::Standard) return std::nullopt;
  return c.depth == DepthRange::NegOneToOne ? glm::frustumRH_NO(l, r, b, t, near, far) : glm::frustumRH_ZO(l, r, b, t, near, far);
}

template <class T>
std::optional<glm::mat<4, 4, T>> engine_ortho(T l, T r, T b, T t, T near, T far, Conv c) {
  const bool rh = c.hand == Handedness::Right, no = c.depth == DepthRange::NegOneToOne;
  if (c.order != DepthOrder::Standard) return std::nullopt;
  if (rh) return no ? glm::orthoRH_NO(l, r, b, t, near, far) : glm::orthoRH_ZO(l, r, b, t, near, far);
  return no ? glm::orthoLH_NO(l, r, b, t, near, far) : glm::orthoLH_ZO(l, r, b, t, near, far);
}

template <class T>
MathFunctions<T> glm_functions() {
  using M = typename MathFunctions<T>::Matrix;
  const auto g = [](const Vec4<T>& v) { return glm::vec<4, T>(v[0], v[1], v[2], v[3]); };
  MathFunctions<T> f;
  f.shadow_matrix = [g](const Vec4<T>& p, const Vec4<T>& l) -> M {
    return from_glm(engine_shadow_matrix(g(p), g(l)));
  };
  f.shadow_matrix_d3dx = [g](const Vec4<T>& p, const Vec4<T>& l) -> M {
    return from_glm(glm::transpose(engine_shadow_matrix(g(p), g(l))));
  };
  f.perspective = [](T fovy, T aspect, T near, T far, Conv c) -> M {
    const auto m = engine_perspective(fovy, aspect, near, far, c);
    return m ? M(from_glm(*m)) : std::nullopt;
  };
  f.perspective_infinite = [](T fovy, T aspect, T near, T eps, Conv c) -> M {
    const auto m = engine_perspective_infinite(fovy, aspect, near, eps, c);
    return m ? M(from_glm(*m)) : std::nullopt;
  };
  f.frustum = [](T l, T r, T b, T t, T near, T far, Conv c) -> M {
    const auto m = engine_frustum(l, r, b, t, near, far, c);
    return m ? M(from_glm(*m)) : std::nullopt;
  };
  f.ortho = [](T l, T r, T b, T t, T near, T far, Conv c) -> M {
    const auto m = engine_ortho(l, r, b, t, near, far, c);
    return m ? M(from_glm(*m)) : std::nullopt;
  };
  f.finite_conventions = {{Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Standard},
                          {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Standard},
                          {Handedness::Left, DepthRange::NegOneToOne, DepthOrder::Standard},
                          {Handedness::Left, DepthRange::ZeroToOne, DepthOrder::Standard}};
  f.infinite_conventions = {{Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Standard}};
  f.frustum_conventions = {{Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Standard},
                           {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Standard}};
  f.ortho_conventions = f.finite_conventions;
  return f;
}

}  // namespace

const MathAdapter& math_adapter_under_test() {
  static const MathAdapter adapter{"GLM-style engine (example adapter)", glm_functions<float>(), glm_functions<double>()};
  return adapter;
}

}  // namespace shadowref::prop
