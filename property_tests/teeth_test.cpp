// teeth_test.cpp — the math properties have teeth: each deliberately wrong implementation below is
// an adapter, and the SAME property code that passes on shadowref's mathlib (and on the GLM
// example) must find a counterexample for it. A wrong variant that slips through fails this test.
//
// The wrong variants, each a mistake found in the wild:
//   * the shadow matrix with the sign of P·L flipped (S = −(P·L) I − L Pᵀ), a published
//     documentation error of D3DXMatrixShadow's formula;
//   * the plane left unnormalised (S = (P·L) I − L Pᵀ with the raw (a, b, c, d));
//   * the transpose forgotten: the "D3DX layout" function returns the canonical matrix;
//   * an infinite projection with GLM's default epsilon (2^-23) in float, whatever epsilon is asked;
//   * the perspective built from the horizontal field of view: the vertical angle it is given taken
//     as the horizontal one, i.e. built with fovy' = 2 atan(tan(fovy/2) aspect);
//   * the perspective with the aspect inverted (height / width);
//   * GLM 0.9.9.8's off-centre left-handed frustum, which keeps the right-handed sign of
//     (r+l)/(r−l) and (t+b)/(t−b) (frustumLH_NO / frustumLH_ZO);
//   * the perspective of the other handedness (an LH matrix for an RH request and vice versa).
#define GLM_FORCE_SILENT_WARNINGS
#include <glm/ext/matrix_clip_space.hpp>

#include "adapters/shadowref_adapter.hpp"
#include "math_properties.hpp"
#include "shadowref/glm_interop.hpp"

namespace shadowref::prop {
namespace {

// Counterexamples must turn up within this many cases (a few times the default run, so the test
// stays well under a second; the wrong variants below are all caught in far fewer).
constexpr int kTeethCases = 1000;

template <class T>
Mat4<T> raw_shadow_matrix(const Vec4<T>& p, const Vec4<T>& l, T sign) {
  Mat4<T> s = -l * p.transpose();
  s.diagonal().array() += sign * p.dot(l);
  return s;
}

template <class T>
MathFunctions<T> sign_flipped() {
  auto f = shadowref_math_functions<T>();
  f.shadow_matrix = [](const Vec4<T>& p, const Vec4<T>& l) -> std::optional<Mat4<T>> {
    return raw_shadow_matrix<T>(p / p.template head<3>().norm(), l, T(-1));
  };
  return f;
}

template <class T>
MathFunctions<T> unnormalised() {
  auto f = shadowref_math_functions<T>();
  f.shadow_matrix = [](const Vec4<T>& p, const Vec4<T>& l) -> std::optional<Mat4<T>> {
    return raw_shadow_matrix<T>(p, l, T(1));
  };
  return f;
}

template <class T>
MathFunctions<T> transpose_forgotten() {
  auto f = shadowref_math_functions<T>();
  f.shadow_matrix_d3dx = f.shadow_matrix;
  return f;
}

template <class T>
MathFunctions<T> glm_default_epsilon() {
  auto f = shadowref_math_functions<T>();
  f.perspective_infinite = [](T fovy, T aspect, T near, T, ClipConvention) -> std::optional<Mat4<T>> {
    return from_glm(glm::tweakedInfinitePerspective(fovy, aspect, near));  // epsilon = 2^-23
  };
  f.infinite_conventions = {kOpenGL};
  return f;
}

template <class T>
MathFunctions<T> fovx_used_as_fovy() {
  auto f = shadowref_math_functions<T>();
  f.perspective = [](T fovy, T aspect, T near, T far, ClipConvention c) -> std::optional<Mat4<T>> {
    const auto m = perspective(T(2) * std::atan(std::tan(fovy / T(2)) * aspect), aspect, near, far, c);
    return m ? std::optional<Mat4<T>>(*m) : std::nullopt;
  };
  return f;
}

template <class T>
MathFunctions<T> aspect_inverted() {
  auto f = shadowref_math_functions<T>();
  f.perspective = [](T fovy, T aspect, T near, T far, ClipConvention c) -> std::optional<Mat4<T>> {
    const auto m = perspective(fovy, T(1) / aspect, near, far, c);
    return m ? std::optional<Mat4<T>>(*m) : std::nullopt;
  };
  return f;
}

template <class T>
MathFunctions<T> glm_off_centre_left_handed_frustum() {
  auto f = shadowref_math_functions<T>();
  const auto right_handed = f.frustum;
  f.frustum = [right_handed](T l, T r, T b, T t, T near, T far, ClipConvention c) -> std::optional<Mat4<T>> {
    if (c.hand == Handedness::Right) return right_handed(l, r, b, t, near, far, c);  // GLM's RH equals ours
    Mat4<T> m = from_glm(c.depth == DepthRange::NegOneToOne ? glm::frustumLH_NO(l, r, b, t, near, far)
                                                            : glm::frustumLH_ZO(l, r, b, t, near, far));
    if (c.order == DepthOrder::Reversed) m.row(2) = m.row(3) - m.row(2);  // reversed-Z as projection.hpp makes it
    return m;
  };
  return f;
}

template <class T>
MathFunctions<T> handedness_swapped() {
  auto f = shadowref_math_functions<T>();
  f.perspective = [](T fovy, T aspect, T near, T far, ClipConvention c) -> std::optional<Mat4<T>> {
    c.hand = c.hand == Handedness::Right ? Handedness::Left : Handedness::Right;
    const auto m = perspective(fovy, aspect, near, far, c);
    return m ? std::optional<Mat4<T>>(*m) : std::nullopt;
  };
  return f;
}

template <class T>
class Teeth : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(Teeth, Scalars);

TYPED_TEST(Teeth, SignOfPLFlippedIsCaughtByProjectedPointLiesOnPlane) {
  const auto f = sign_flipped<TypeParam>();
  expect_counterexample([&] { projected_point_lies_on_plane<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, SignOfPLFlippedIsCaughtByLightIsInTheKernel) {
  const auto f = sign_flipped<TypeParam>();
  expect_counterexample([&] { light_is_in_the_kernel<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, SignOfPLFlippedIsCaughtByPointsOnPlaneStay) {
  const auto f = sign_flipped<TypeParam>();
  expect_counterexample([&] { points_on_plane_stay<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, UnnormalisedPlaneIsCaughtByProjectingTwiceIsProjectingOnce) {
  const auto f = unnormalised<TypeParam>();
  expect_counterexample([&] { projecting_twice_is_projecting_once<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, UnnormalisedPlaneIsCaughtByPointsOnPlaneStay) {
  const auto f = unnormalised<TypeParam>();
  expect_counterexample([&] { points_on_plane_stay<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, TransposeForgottenIsCaughtByD3dxLayoutIsTheTranspose) {
  const auto f = transpose_forgotten<TypeParam>();
  expect_counterexample([&] { d3dx_layout_is_the_transpose<TypeParam>(f); }, kTeethCases);
}

TYPED_TEST(Teeth, FovxUsedAsFovyIsCaughtByPerspectiveMapsTheFieldOfViewOntoTheNdcSquare) {
  const auto f = fovx_used_as_fovy<TypeParam>();
  expect_counterexample([&] { perspective_maps_the_field_of_view_onto_the_ndc_square<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, FovxUsedAsFovyIsCaughtByNdcXyDoNotDependOnTheDepthParameters) {
  const auto f = fovx_used_as_fovy<TypeParam>();
  expect_counterexample([&] { ndc_xy_do_not_depend_on_the_depth_parameters<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, AspectInvertedIsCaughtByPerspectiveMapsTheFieldOfViewOntoTheNdcSquare) {
  const auto f = aspect_inverted<TypeParam>();
  expect_counterexample([&] { perspective_maps_the_field_of_view_onto_the_ndc_square<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, AspectInvertedIsCaughtByNdcXyDoNotDependOnTheDepthParameters) {
  const auto f = aspect_inverted<TypeParam>();
  expect_counterexample([&] { ndc_xy_do_not_depend_on_the_depth_parameters<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, GlmOffCentreLeftHandedFrustumIsCaughtByFrustumMapsItsNearRectangleOntoTheNdcSquare) {
  const auto f = glm_off_centre_left_handed_frustum<TypeParam>();
  expect_counterexample([&] { frustum_maps_its_near_rectangle_onto_the_ndc_square<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(Teeth, HandednessSwappedIsCaughtByPointsInFrontOfTheEyeAreInFront) {
  const auto f = handedness_swapped<TypeParam>();
  expect_counterexample([&] { points_in_front_of_the_eye_are_in_front<TypeParam>(f); }, kTeethCases);
}

// GLM's default epsilon is only too small in float (in double 2^-23 is ample): float only.
TEST(TeethFloat, GlmDefaultEpsilonIsCaughtByDirectionsSurviveTheInfiniteFarPlane) {
  const auto f = glm_default_epsilon<float>();
  expect_counterexample([&] { directions_survive_the_infinite_far_plane<float>(f); }, kTeethCases);
}

}  // namespace
}  // namespace shadowref::prop
