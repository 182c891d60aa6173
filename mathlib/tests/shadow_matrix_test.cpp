// Unit tests of shadowref/shadow_matrix.hpp: the D3DX listing field by field, closed-form hand
// cases, the defining identities, and every degenerate input.
#include "shadowref/shadow_matrix.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "scalar_types.hpp"

namespace shadowref {
namespace {

using test::eps;

// The classic CreateShadowMatrix listing (the D3DXMatrixShadow code path), written out
// independently of shadow_matrix(): row-vector layout, fields _11 … _44, plane normalised by
// |(a, b, c)| first. Returned as m[r][c] = _{r+1}{c+1}.
template <class T>
std::array<std::array<T, 4>, 4> create_shadow_matrix_listing(Vec4<T> plane, const Vec4<T>& light) {
  const T len = std::sqrt(plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2]);
  const T a = plane[0] / len, b = plane[1] / len, c = plane[2] / len, d = plane[3] / len;
  const T fDot = a * light.x() + b * light.y() + c * light.z() + d * light.w();
  std::array<std::array<T, 4>, 4> m{};
  m[0] = {fDot - light.x() * a, -light.y() * a, -light.z() * a, -light.w() * a};
  m[1] = {-light.x() * b, fDot - light.y() * b, -light.z() * b, -light.w() * b};
  m[2] = {-light.x() * c, -light.y() * c, fDot - light.z() * c, -light.w() * c};
  m[3] = {-light.x() * d, -light.y() * d, -light.z() * d, fDot - light.w() * d};
  return m;
}

template <class T>
Vec3<T> project(const Mat4<T>& s, const Vec3<T>& p) {
  const Vec4<T> h = s * Vec4<T>(p.x(), p.y(), p.z(), T(1));
  return h.template head<3>() / h.w();
}

template <class T>
class ShadowMatrixTest : public ::testing::Test {};
TYPED_TEST_SUITE(ShadowMatrixTest, test::Scalars);

TYPED_TEST(ShadowMatrixTest, D3dxLayoutEqualsTheCreateShadowMatrixListingFieldByField) {
  using T = TypeParam;
  const Vec4<T> planes[] = {{0, 1, 0, 0}, {0, 2, 0, -1}, {1, 2, 3, 4}, {T(-0.3), T(0.9), T(0.1), T(2.5)}};
  const Vec4<T> lights[] = {{2, 6, 1, 1}, {T(0.5), 4, T(-3), 1}, {1, 1, T(0.25), 0}, {T(-2), 5, 7, 1}};
  for (const auto& pv : planes)
    for (const auto& l : lights) {
      const auto p = plane_from_coefficients(pv[0], pv[1], pv[2], pv[3]);
      ASSERT_TRUE(p.ok());
      const auto s = shadow_matrix_d3dx(*p, l);
      ASSERT_TRUE(s.ok()) << s.message();
      const auto listing = create_shadow_matrix_listing(pv, l);
      const T pl = std::abs(normalize(*p)->abcd.dot(l));
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
          const T ours = (*s)(r, c), theirs = listing[r][c];
          if (r != c) {
            // Off the diagonal both compute the same single product -L_c * P_r of the same
            // normalised coefficients (normalisation is the same sqrt and division): bit-equal.
            EXPECT_EQ(ours, theirs) << "_" << r + 1 << c + 1;
          } else {
            // On the diagonal P·L is a 4-term sum that Eigen may add in another order (SIMD):
            // the two sums differ by at most the 4-term error bound, 4 ε Σ|P_i L_i|.
            const T scale = normalize(*p)->abcd.cwiseAbs().dot(l.cwiseAbs()) + pl;
            EXPECT_CLOSE(ours, theirs, eps<T>(4, scale)) << "_" << r + 1 << c + 1;
          }
        }
    }
}

TYPED_TEST(ShadowMatrixTest, CanonicalIsTheTransposeOfD3dx) {
  using T = TypeParam;
  const Plane<T> p{Vec4<T>(1, 2, 3, 4)};
  const Vec4<T> l(T(0.5), 4, -3, 1);
  EXPECT_EQ(Mat4<T>(shadow_matrix(p, l)->transpose()), *shadow_matrix_d3dx(p, l));
}

TYPED_TEST(ShadowMatrixTest, HandCasePointLightStraightAboveGround) {
  using T = TypeParam;
  // Plane y = 0, light at (0, 10, 0). A point (1, 5, 0) halfway down casts its shadow twice as far
  // out, at (2, 0, 0): the ray L + t (p − L) meets y = 0 at t = 2. S = 10 I − L Pᵀ exactly.
  const Plane<T> ground{Vec4<T>(0, 1, 0, 0)};
  const Vec4<T> light(0, 10, 0, 1);
  const auto s = shadow_matrix(ground, light);
  ASSERT_TRUE(s.ok());
  Mat4<T> expected;
  expected << 10, 0, 0, 0,  //
      0, 0, 0, 0,           //
      0, 0, 10, 0,          //
      0, -1, 0, 10;
  EXPECT_EQ(*s, expected);  // every entry is a small integer: exact in every scalar type
  EXPECT_EQ(project(*s, Vec3<T>(1, 5, 0)), Vec3<T>(2, 0, 0));
  EXPECT_EQ(project(*s, Vec3<T>(-3, 5, 4)), Vec3<T>(-6, 0, 8));
}

TYPED_TEST(ShadowMatrixTest, HandCaseDirectionalLightProjectsStraightDown) {
  using T = TypeParam;
  const Plane<T> ground{Vec4<T>(0, 1, 0, 0)};
  const auto s = shadow_matrix(ground, Vec4<T>(0, 1, 0, 0));  // sun at the zenith
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(project(*s, Vec3<T>(3, 7, -2)), Vec3<T>(3, 0, -2));
  // A sun at 45 degrees toward +x: a point at height h lands h further toward -x.
  const auto s45 = shadow_matrix(ground, Vec4<T>(1, 1, 0, 0));
  EXPECT_EQ(project(*s45, Vec3<T>(3, 2, 5)), Vec3<T>(1, 0, 5));
}

TYPED_TEST(ShadowMatrixTest, DefiningIdentities) {
  using T = TypeParam;
  const Plane<T> p{Vec4<T>(T(0.2), 1, T(-0.4), T(0.7))};
  const Vec4<T> l(T(1.5), 6, T(-2), 1);
  const Mat4<T> s = *shadow_matrix(p, l);
  const Plane<T> unit = *normalize(p);
  const T pl = dot(unit, l);
  // Entries are O(|P||L|) ≈ 7 here and each identity is a few 4-term dot products of them.
  const T tol = eps<T>(32, T(50));
  EXPECT_TRUE((test::near_matrix(s * l, Vec4<T>::Zero(), tol))) << "S L = 0";
  EXPECT_TRUE((test::near_matrix(s * s, pl * s, eps<T>(64, T(400))))) << "S² = (P·L) S";
  for (const Vec3<T>& q : {Vec3<T>(1, 2, 3), Vec3<T>(-4, T(0.5), 2), Vec3<T>(T(0.1), 3, T(-7))}) {
    const Vec3<T> shadow = project(s, q);
    EXPECT_CLOSE(dot_coord(unit, shadow), T(0), eps<T>(64, T(10))) << "the shadow lies on the plane";
    // Light, point and shadow are collinear: (q − L) × (shadow − L) = 0 relative to their lengths.
    const Vec3<T> lq = q - l.template head<3>(), ls = shadow - l.template head<3>();
    EXPECT_LE(lq.cross(ls).norm(), eps<T>(128, lq.norm() * ls.norm())) << "collinear";
  }
  // A point on the plane stays where it is (up to the homogeneous divide).
  const Vec3<T> on_plane(2, -T(0.7) - T(0.2) * 2, 0);  // 0.2·2 + y + 0.7 = 0 with c z = 0
  EXPECT_TRUE((test::near_matrix(project(s, on_plane), on_plane, eps<T>(64, T(4)))));
}

TYPED_TEST(ShadowMatrixTest, ScalingThePlaneChangesNothing) {
  using T = TypeParam;
  const Vec4<T> l(T(1.5), 6, T(-2), 1);
  const Mat4<T> s1 = *shadow_matrix(Plane<T>{Vec4<T>(0, 1, 0, T(0.5))}, l);
  const Mat4<T> s4 = *shadow_matrix(Plane<T>{Vec4<T>(0, 4, 0, 2)}, l);
  EXPECT_EQ(s1, s4);  // 4 and 2 normalise exactly to 1 and 0.5 (powers of two)
}

TYPED_TEST(ShadowMatrixTest, GeometryBeyondThePointLightProjectsToNegativeW) {
  using T = TypeParam;
  // A point above the light projects "through" it: w = P·L − P·v = 10 − 20 < 0, which a GPU clips.
  // That is the technique's false-shadow case (the catalogue shows it), not an error here.
  const Mat4<T> s = *shadow_matrix(Plane<T>{Vec4<T>(0, 1, 0, 0)}, Vec4<T>(0, 10, 0, 1));
  EXPECT_LT((s * Vec4<T>(1, 20, 0, 1)).w(), T(0));
  EXPECT_GT((s * Vec4<T>(1, 5, 0, 1)).w(), T(0));
}

TYPED_TEST(ShadowMatrixTest, DegenerateInputIsRefusedWithAReason) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  const Plane<T> ground{Vec4<T>(0, 1, 0, 0)};
  EXPECT_EQ(shadow_matrix(Plane<T>{Vec4<T>(0, 0, 0, 1)}, Vec4<T>(0, 5, 0, 1)).error(), Error::ZeroNormal);
  EXPECT_EQ(shadow_matrix(ground, Vec4<T>(0, 0, 0, 0)).error(), Error::ZeroLight);
  EXPECT_EQ(shadow_matrix(ground, Vec4<T>(3, 0, 2, 1)).error(), Error::LightOnPlane);   // point light on y = 0
  EXPECT_EQ(shadow_matrix(ground, Vec4<T>(1, 0, 0, 0)).error(), Error::LightOnPlane);   // sun on the horizon
  EXPECT_EQ(shadow_matrix(ground, Vec4<T>(nan, 5, 0, 1)).error(), Error::NonFinite);
  EXPECT_EQ(shadow_matrix(Plane<T>{Vec4<T>(0, inf, 0, 0)}, Vec4<T>(0, 5, 0, 1)).error(), Error::NonFinite);
  EXPECT_EQ(shadow_matrix_d3dx(ground, Vec4<T>(1, 0, 0, 0)).error(), Error::LightOnPlane);
  // P·L that is pure rounding noise counts as zero: the light at 0.1 on the plane x + y = 0.1
  // computed through a normalised plane whose coefficients are inexact.
  const Plane<T> slanted{Vec4<T>(1, 1, 0, -T(0.1) - T(0.2))};
  EXPECT_EQ(shadow_matrix(slanted, Vec4<T>(T(0.1), T(0.2), 0, 1)).error(), Error::LightOnPlane);
  // A light just off the plane is fine, and its matrix is finite.
  const auto near_plane = shadow_matrix(ground, Vec4<T>(0, T(1e-3), 0, 1));
  ASSERT_TRUE(near_plane.ok());
  EXPECT_TRUE(near_plane->allFinite());
}

}  // namespace
}  // namespace shadowref
