// Unit tests of shadowref/projection.hpp.
//
// Two independent kinds of evidence: (1) term-by-term equality with GLM 0.9.9.8 wherever GLM has
// the function; (2) the geometric definition, checked without any formula: the corners of the near
// and far rectangles land on the NDC corners at the depth the convention promises. Where GLM has
// no such function (0..1 infinite) or a different answer (off-centre LH frustum) or a weak default
// (tweakedInfinitePerspective's epsilon in float), a test below says so.
#include "shadowref/projection.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>  // inverse()
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/gtc/epsilon.hpp>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "scalar_types.hpp"
#include "shadowref/glm_interop.hpp"

namespace shadowref {
namespace {

using test::eps;

constexpr ClipConvention kAll[] = {
    {Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Standard},
    {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Standard},
    {Handedness::Left, DepthRange::NegOneToOne, DepthOrder::Standard},
    {Handedness::Left, DepthRange::ZeroToOne, DepthOrder::Standard},
    {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Reversed},
    {Handedness::Left, DepthRange::ZeroToOne, DepthOrder::Reversed},
};

std::string name(const ClipConvention& c) {
  return std::string(to_string(c.hand)) + " " + to_string(c.depth) + " " + to_string(c.order);
}

// The NDC depth a convention promises for the near and the far plane.
template <class T>
std::pair<T, T> promised_depths(const ClipConvention& c) {
  if (c.order == DepthOrder::Reversed) return {T(1), T(0)};
  return {c.depth == DepthRange::NegOneToOne ? T(-1) : T(0), T(1)};
}

// A view-space point at distance `dist` in front of the eye, at NDC position (sx, sy) of a
// frustum with near-plane half-extents (hx, hy) at distance `near`.
template <class T>
Vec4<T> view_point(const ClipConvention& c, T sx, T sy, T hx, T hy, T near, T dist, T cx = 0, T cy = 0) {
  const T k = dist / near;
  const T z = c.hand == Handedness::Right ? -dist : dist;
  return Vec4<T>((cx + sx * hx) * k, (cy + sy * hy) * k, z, T(1));
}

template <class T>
Vec3<T> ndc(const Mat4<T>& m, const Vec4<T>& v) {
  const Vec4<T> c = m * v;
  return c.template head<3>() / c.w();
}

template <class T>
class ProjectionTest : public ::testing::Test {};
TYPED_TEST_SUITE(ProjectionTest, test::Scalars);

TYPED_TEST(ProjectionTest, PerspectiveMapsTheFrustumCornersWhereTheConventionSays) {
  using T = TypeParam;
  const T fovy = std::numbers::pi_v<T> / T(3), aspect = T(1.5), n = T(0.25), f = T(64);
  const T hy = std::tan(fovy / T(2)) * n, hx = hy * aspect;
  for (const ClipConvention& c : kAll) {
    const auto m = perspective(fovy, aspect, n, f, c);
    ASSERT_TRUE(m.ok()) << name(c);
    const auto [zn, zf] = promised_depths<T>(c);
    for (T sx : {T(-1), T(1)})
      for (T sy : {T(-1), T(1)}) {
        // Corner mapping goes through tan, a few products and one division: 64 ε covers it with
        // room; the far corner's depth loses log2(f/n) bits to the (f − n) cancellation.
        const Vec3<T> a = ndc(*m, view_point(c, sx, sy, hx, hy, n, n));
        const Vec3<T> b = ndc(*m, view_point(c, sx, sy, hx, hy, n, f));
        EXPECT_TRUE((test::near_matrix(a, Vec3<T>(sx, sy, zn), eps<T>(64)))) << name(c);
        EXPECT_TRUE((test::near_matrix(b, Vec3<T>(sx, sy, zf), eps<T>(64, f / n)))) << name(c);
      }
  }
}

TYPED_TEST(ProjectionTest, FrustumMapsOffCentreCornersWhereTheConventionSays) {
  using T = TypeParam;
  const T l = T(-0.5), r = T(1.5), b = T(-0.25), t = T(0.75), n = T(0.5), f = T(32);
  for (const ClipConvention& c : kAll) {
    const auto m = frustum(l, r, b, t, n, f, c);
    ASSERT_TRUE(m.ok()) << name(c);
    const auto [zn, zf] = promised_depths<T>(c);
    const T hx = (r - l) / 2, hy = (t - b) / 2, cx = (r + l) / 2, cy = (t + b) / 2;
    for (T sx : {T(-1), T(1)})
      for (T sy : {T(-1), T(1)}) {
        const Vec3<T> a = ndc(*m, view_point(c, sx, sy, hx, hy, n, n, cx, cy));
        const Vec3<T> z = ndc(*m, view_point(c, sx, sy, hx, hy, n, f, cx, cy));
        EXPECT_TRUE((test::near_matrix(a, Vec3<T>(sx, sy, zn), eps<T>(64)))) << name(c);
        EXPECT_TRUE((test::near_matrix(z, Vec3<T>(sx, sy, zf), eps<T>(64, f / n)))) << name(c);
      }
  }
}

TYPED_TEST(ProjectionTest, OrthoMapsTheBoxCornersWhereTheConventionSays) {
  using T = TypeParam;
  const T l = -3, r = 5, b = -1, t = 2, n = T(-4), f = 12;  // ortho allows near <= 0
  for (const ClipConvention& c : kAll) {
    const auto m = ortho(l, r, b, t, n, f, c);
    ASSERT_TRUE(m.ok()) << name(c);
    const auto [zn, zf] = promised_depths<T>(c);
    const T zs = c.hand == Handedness::Right ? T(-1) : T(1);
    const Vec3<T> a = ndc(*m, Vec4<T>(l, b, zs * n, 1));
    const Vec3<T> z = ndc(*m, Vec4<T>(r, t, zs * f, 1));
    EXPECT_TRUE((test::near_matrix(a, Vec3<T>(-1, -1, zn), eps<T>(16)))) << name(c);
    EXPECT_TRUE((test::near_matrix(z, Vec3<T>(1, 1, zf), eps<T>(16)))) << name(c);
  }
}

TYPED_TEST(ProjectionTest, InfiniteFormsHaveTheDocumentedRowsAndAreTheLimitOfTheFiniteOnes) {
  using T = TypeParam;
  const T fovy = std::numbers::pi_v<T> / T(4), aspect = T(2), n = T(0.5);
  for (const ClipConvention& c : kAll) {
    const auto inf = perspective_infinite(fovy, aspect, n, c);
    ASSERT_TRUE(inf.ok()) << name(c);
    const T s = c.hand == Handedness::Right ? T(-1) : T(1);
    // The documented rows, exactly (no rounding: products of n with small integers).
    Vec4<T> row2, row3(0, 0, s, 0);
    if (c.order == DepthOrder::Reversed) row2 = Vec4<T>(0, 0, 0, n);
    else if (c.depth == DepthRange::NegOneToOne) row2 = Vec4<T>(0, 0, s, -2 * n);
    else row2 = Vec4<T>(0, 0, s, -n);
    EXPECT_EQ(Vec4<T>(inf->row(2).transpose()), row2) << name(c);
    EXPECT_EQ(Vec4<T>(inf->row(3).transpose()), row3) << name(c);
    // The limit: with far = 1/ε_T⁻¹ … the finite matrix differs by O(n / far).
    const T far = T(1) / std::sqrt(std::numeric_limits<T>::epsilon());
    const auto fin = perspective(fovy, aspect, n, far, c);
    EXPECT_TRUE((test::near_matrix(*fin, *inf, T(4) * n / far))) << name(c);
  }
}

TYPED_TEST(ProjectionTest, EpsilonRowsAreLengyels) {
  using T = TypeParam;
  const T n = T(0.5), e = T(1) / T(1024);
  const T fovy = std::numbers::pi_v<T> / T(2);
  const auto rh_no = perspective_infinite(fovy, T(1), n, {Handedness::Right, DepthRange::NegOneToOne}, e);
  const auto rh_zo = perspective_infinite(fovy, T(1), n, {Handedness::Right, DepthRange::ZeroToOne}, e);
  const auto lh_no = perspective_infinite(fovy, T(1), n, {Handedness::Left, DepthRange::NegOneToOne}, e);
  EXPECT_EQ(Vec4<T>(rh_no->row(2).transpose()), Vec4<T>(0, 0, e - 1, (e - 2) * n));
  EXPECT_EQ(Vec4<T>(rh_zo->row(2).transpose()), Vec4<T>(0, 0, e - 1, (e - 1) * n));
  EXPECT_EQ(Vec4<T>(lh_no->row(2).transpose()), Vec4<T>(0, 0, 1 - e, (e - 2) * n));
  // A direction straight ahead (w = 0) lands strictly inside the far plane: depth 1 − ε.
  const Vec4<T> ahead(0, 0, -1, 0);
  const Vec4<T> clip = *rh_no * ahead;
  EXPECT_EQ(clip.z() / clip.w(), 1 - e);
}

TYPED_TEST(ProjectionTest, DegenerateInputIsRefusedWithAReason) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  const T fovy = T(1);
  EXPECT_EQ(perspective<T>(fovy, 1, 0, 10).error(), Error::NearNotPositive);
  EXPECT_EQ(perspective<T>(fovy, 1, -1, 10).error(), Error::NearNotPositive);
  EXPECT_EQ(perspective<T>(fovy, 1, 10, 10).error(), Error::FarNotBeyondNear);
  EXPECT_EQ(perspective<T>(fovy, 1, 10, 1).error(), Error::FarNotBeyondNear);
  EXPECT_EQ(perspective<T>(fovy, 0, 1, 10).error(), Error::ZeroAspect);
  EXPECT_EQ(perspective<T>(0, 1, 1, 10).error(), Error::FovOutOfRange);
  EXPECT_EQ(perspective<T>(std::numbers::pi_v<T>, 1, 1, 10).error(), Error::FovOutOfRange);
  EXPECT_EQ(perspective<T>(nan, 1, 1, 10).error(), Error::NonFinite);
  EXPECT_EQ(perspective<T>(fovy, 1, 1, inf).error(), Error::NonFinite);  // infinite far: use perspective_infinite
  EXPECT_EQ(perspective<T>(fovy, 1, 1, 10, {Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Reversed}).error(),
            Error::ReversedNeedsZeroToOne);
  EXPECT_EQ(perspective_infinite<T>(fovy, 1, 0).error(), Error::NearNotPositive);
  EXPECT_EQ(perspective_infinite<T>(fovy, 1, 1, {}, T(1)).error(), Error::EpsilonOutOfRange);
  EXPECT_EQ(perspective_infinite<T>(fovy, 1, 1, {}, T(-0.5)).error(), Error::EpsilonOutOfRange);
  EXPECT_EQ(perspective_infinite<T>(fovy, -2, 1).error(), Error::ZeroAspect);
  EXPECT_EQ(frustum<T>(1, 1, -1, 1, 1, 10).error(), Error::EmptyFrustum);
  EXPECT_EQ(frustum<T>(-1, 1, -1, 1, 0, 10).error(), Error::NearNotPositive);
  EXPECT_EQ(frustum_infinite<T>(-1, 1, 2, 2, 1).error(), Error::EmptyFrustum);
  EXPECT_EQ(ortho<T>(-1, 1, -1, 1, 5, 5).error(), Error::FarNotBeyondNear);
  EXPECT_EQ(ortho<T>(-1, 1, -1, 1, nan, 5).error(), Error::NonFinite);
  // Extreme but finite input whose matrix would overflow is refused, never returned as inf.
  EXPECT_EQ(perspective<T>(fovy, std::numeric_limits<T>::denorm_min(), 1, 10).error(), Error::NonFinite);
}

// ---------------------------------------------------------------- against GLM 0.9.9.8

template <class T>
class GlmAgreementTest : public ::testing::Test {};
TYPED_TEST_SUITE(GlmAgreementTest, test::FloatAndDouble);

TYPED_TEST(GlmAgreementTest, FinitePerspectiveIsBitIdenticalToGlm) {
  using T = TypeParam;
  for (T fovy : {T(0.3), T(1), T(2.5)})
    for (T aspect : {T(0.75), T(16) / T(9)})
      for (auto [n, f] : {std::pair<T, T>{T(0.1), T(100)}, {T(1), T(3)}, {T(0.01), T(1e5)}}) {
        // Same expression order as GLM, so the same float operations: exact equality.
        EXPECT_EQ(*perspective(fovy, aspect, n, f, {Handedness::Right, DepthRange::NegOneToOne}),
                  from_glm(glm::perspectiveRH_NO(fovy, aspect, n, f)));
        EXPECT_EQ(*perspective(fovy, aspect, n, f, {Handedness::Right, DepthRange::ZeroToOne}),
                  from_glm(glm::perspectiveRH_ZO(fovy, aspect, n, f)));
        EXPECT_EQ(*perspective(fovy, aspect, n, f, {Handedness::Left, DepthRange::NegOneToOne}),
                  from_glm(glm::perspectiveLH_NO(fovy, aspect, n, f)));
        EXPECT_EQ(*perspective(fovy, aspect, n, f, {Handedness::Left, DepthRange::ZeroToOne}),
                  from_glm(glm::perspectiveLH_ZO(fovy, aspect, n, f)));
      }
}

TYPED_TEST(GlmAgreementTest, OrthoIsBitIdenticalToGlm) {
  using T = TypeParam;
  const T l = -3, r = 5, b = -1, t = 2, n = T(0.5), f = 12;
  EXPECT_EQ(*ortho(l, r, b, t, n, f, {Handedness::Right, DepthRange::NegOneToOne}), from_glm(glm::orthoRH_NO(l, r, b, t, n, f)));
  EXPECT_EQ(*ortho(l, r, b, t, n, f, {Handedness::Right, DepthRange::ZeroToOne}), from_glm(glm::orthoRH_ZO(l, r, b, t, n, f)));
  EXPECT_EQ(*ortho(l, r, b, t, n, f, {Handedness::Left, DepthRange::NegOneToOne}), from_glm(glm::orthoLH_NO(l, r, b, t, n, f)));
  EXPECT_EQ(*ortho(l, r, b, t, n, f, {Handedness::Left, DepthRange::ZeroToOne}), from_glm(glm::orthoLH_ZO(l, r, b, t, n, f)));
}

TYPED_TEST(GlmAgreementTest, FrustumMatchesGlmExceptGlmsOffCentreLeftHandedSign) {
  using T = TypeParam;
  const T n = T(0.5), f = 32;
  // Centred: all four equal GLM bit for bit.
  EXPECT_EQ(*frustum<T>(-1, 1, -1, 1, n, f, {Handedness::Right, DepthRange::NegOneToOne}), from_glm(glm::frustumRH_NO<T>(-1, 1, -1, 1, n, f)));
  EXPECT_EQ(*frustum<T>(-1, 1, -1, 1, n, f, {Handedness::Right, DepthRange::ZeroToOne}), from_glm(glm::frustumRH_ZO<T>(-1, 1, -1, 1, n, f)));
  EXPECT_EQ(*frustum<T>(-1, 1, -1, 1, n, f, {Handedness::Left, DepthRange::NegOneToOne}), from_glm(glm::frustumLH_NO<T>(-1, 1, -1, 1, n, f)));
  EXPECT_EQ(*frustum<T>(-1, 1, -1, 1, n, f, {Handedness::Left, DepthRange::ZeroToOne}), from_glm(glm::frustumLH_ZO<T>(-1, 1, -1, 1, n, f)));
  // Off-centre RH: equal.
  const T l = T(-0.5), r = T(1.5), b = T(-0.25), t = T(0.75);
  EXPECT_EQ(*frustum(l, r, b, t, n, f, {Handedness::Right, DepthRange::NegOneToOne}), from_glm(glm::frustumRH_NO(l, r, b, t, n, f)));
  // Off-centre LH: GLM 0.9.9.8 keeps the RH sign on (r+l)/(r−l) and (t+b)/(t−b), so its matrix maps
  // the near rectangle's right edge to ndc.x = 2(r+l)/(r−l) + 1 ≠ 1. DirectXMath's
  // XMMatrixPerspectiveOffCenterLH has −(l+r)/(r−l), as we do (and the corner test above proves ours).
  const Mat4<T> ours = *frustum(l, r, b, t, n, f, {Handedness::Left, DepthRange::NegOneToOne});
  const Mat4<T> glms = from_glm(glm::frustumLH_NO(l, r, b, t, n, f));
  EXPECT_EQ(ours(0, 2), -glms(0, 2)) << "GLM's off-centre LH sign";
  EXPECT_EQ(ours(1, 2), -glms(1, 2));
  const Vec4<T> right_edge(r, 0, n, 1);  // LH: in front is +z
  const Vec4<T> glm_clip = glms * right_edge;
  EXPECT_GT(std::abs(glm_clip.x() / glm_clip.w() - 1), T(0.5)) << "GLM misplaces the off-centre LH frustum";
}

TYPED_TEST(GlmAgreementTest, InfinitePerspectiveMatchesGlmWithinItsDifferentFormula) {
  using T = TypeParam;
  const T fovy = T(1.1), aspect = T(1.25), n = T(0.1);
  // GLM builds 2n / (right − left) from range = tan(fovy/2)·n; we build 1 / (aspect·tan(fovy/2)).
  // The two differ by a few roundings of O(1) values: 8 ε. The z rows are exact in both.
  EXPECT_TRUE((test::near_matrix(*perspective_infinite(fovy, aspect, n, {Handedness::Right, DepthRange::NegOneToOne}),
                                 from_glm(glm::infinitePerspectiveRH(fovy, aspect, n)), eps<T>(8, T(4)))));
  EXPECT_TRUE((test::near_matrix(*perspective_infinite(fovy, aspect, n, {Handedness::Left, DepthRange::NegOneToOne}),
                                 from_glm(glm::infinitePerspectiveLH(fovy, aspect, n)), eps<T>(8, T(4)))));
  const T e = T(1) / T(4096);
  EXPECT_TRUE((test::near_matrix(*perspective_infinite(fovy, aspect, n, {Handedness::Right, DepthRange::NegOneToOne}, e),
                                 from_glm(glm::tweakedInfinitePerspective(fovy, aspect, n, e)), eps<T>(8, T(4)))));
}

TEST(GlmGaps, GlmHasNoZeroToOneInfinitePerspective) {
  // GLM 0.9.9.8's infinitePerspective* ignores GLM_FORCE_DEPTH_ZERO_TO_ONE: there is only the −1..1
  // form. Its near plane maps to −1 while the 0..1 form must map it to 0 — which ours does.
  const float n = 0.5f;
  const Mat4<float> glm_rh = from_glm(glm::infinitePerspectiveRH(1.0f, 1.0f, n));
  const Vec4<float> near_point(0, 0, -n, 1);
  const Vec4<float> g = glm_rh * near_point;
  EXPECT_EQ(g.z() / g.w(), -1.0f) << "GLM's only infinite form is −1..1";
  const Vec4<float> o = *perspective_infinite(1.0f, 1.0f, n, {Handedness::Right, DepthRange::ZeroToOne}) * near_point;
  EXPECT_EQ(o.z() / o.w(), 0.0f);
}

// Directions (w = 0) inside the view frustum of random cameras, pushed through P · V in float as
// a GPU does. Counts those at or beyond the far plane (clip.z >= clip.w) and those beyond it
// (clip.z > clip.w: clipped). Deterministic: a fixed seed and libstdc++'s distributions.
struct FarPlaneCounts {
  long on_or_beyond = 0, beyond = 0, total = 0;
};

FarPlaneCounts directions_at_far_plane(const Mat4<float>& proj) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1, 1);
  FarPlaneCounts counts;
  for (int k = 0; k < 100; ++k) {
    Eigen::Quaternionf q(u(rng), u(rng), u(rng), u(rng));
    q.normalize();
    Mat4<float> view = Mat4<float>::Identity();
    view.block<3, 3>(0, 0) = q.toRotationMatrix();
    view.block<3, 1>(0, 3) = Vec3<float>(u(rng) * 50, u(rng) * 50, u(rng) * 50);
    const Mat4<float> pv = proj * view;
    const Mat4<float> inv_view = view.inverse();
    for (int i = 0; i < 1000; ++i) {
      const Vec4<float> dir_view(u(rng) * 0.5f, u(rng) * 0.5f, -1, 0);  // inside a 1-radian frustum
      const Vec4<float> dir_world = inv_view * dir_view * (1.0f + 100.0f * (u(rng) + 1));
      const Vec4<float> clip = pv * dir_world;
      ++counts.total;
      if (clip.z() >= clip.w()) ++counts.on_or_beyond;
      if (clip.z() > clip.w()) ++counts.beyond;
    }
  }
  return counts;
}

TEST(GlmGaps, GlmsDefaultTweakEpsilonIsTooSmallInFloat) {
  // tweakedInfinitePerspective(fovy, aspect, near) defaults to ε = 2^-23: in float, P · V rounds
  // some directions past the far plane, and the GPU clips extruded shadow-volume vertices.
  const Mat4<float> glm_default = from_glm(glm::tweakedInfinitePerspective(1.0f, 1.0f, 0.1f));
  const Mat4<float> none = *perspective_infinite(1.0f, 1.0f, 0.1f, {});
  const Mat4<float> safe =
      *perspective_infinite(1.0f, 1.0f, 0.1f, {}, static_cast<float>(kSafeInfiniteEpsilonFloat));
  const FarPlaneCounts n = directions_at_far_plane(none), g = directions_at_far_plane(glm_default),
                       s = directions_at_far_plane(safe);
  EXPECT_EQ(n.on_or_beyond, n.total) << "without epsilon every direction sits exactly on the far plane";
  EXPECT_GT(g.beyond, 0) << "GLM's default epsilon lets directions past the far plane (clipped)";
  EXPECT_EQ(s.on_or_beyond, 0) << "kSafeInfiniteEpsilonFloat keeps every direction strictly inside";
}

}  // namespace
}  // namespace shadowref
