// Unit tests of shadowref/plane.hpp: construction, normalisation, the dot products, degenerate input.
#include "shadowref/plane.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "scalar_types.hpp"

namespace shadowref {
namespace {

using test::eps;

template <class T>
class PlaneTest : public ::testing::Test {};
TYPED_TEST_SUITE(PlaneTest, test::Scalars);

TYPED_TEST(PlaneTest, FromCoefficientsKeepsThemAsGiven) {
  using T = TypeParam;
  const auto p = plane_from_coefficients<T>(0, 2, 0, -4);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->abcd, Vec4<T>(0, 2, 0, -4));
  EXPECT_EQ(dot_coord(*p, Vec3<T>(5, 2, 7)), T(0));  // y = 2 lies on 2y - 4 = 0
}

TYPED_TEST(PlaneTest, FromPointNormal) {
  using T = TypeParam;
  const auto p = plane_from_point_normal<T>(Vec3<T>(1, 2, 3), Vec3<T>(0, 0, 2));
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->abcd, Vec4<T>(0, 0, 2, -6));
}

TYPED_TEST(PlaneTest, FromPointsIsCounterClockwiseFromTheFront) {
  using T = TypeParam;
  // Counter-clockwise seen from +y (x to -z is a left turn when looking down from above): normal +y.
  const auto p = plane_from_points<T>(Vec3<T>(0, 1, 0), Vec3<T>(0, 1, 1), Vec3<T>(1, 1, 0));
  ASSERT_TRUE(p.ok());
  EXPECT_GT(p->b(), T(0));
  EXPECT_EQ(p->a(), T(0));
  EXPECT_EQ(p->c(), T(0));
  EXPECT_EQ(dot_coord(*p, Vec3<T>(3, 1, -8)), T(0));
  EXPECT_GT(dot_coord(*p, Vec3<T>(0, 2, 0)), T(0));
}

TYPED_TEST(PlaneTest, NormalizeGivesUnitNormalAndSignedDistance) {
  using T = TypeParam;
  const auto p = plane_from_coefficients<T>(3, 0, 4, -10);  // |n| = 5
  ASSERT_TRUE(p.ok());
  const auto n = normalize(*p);
  ASSERT_TRUE(n.ok());
  // One division per coefficient: each is correctly rounded, within half an ulp.
  EXPECT_CLOSE(n->a(), T(3) / T(5), eps<T>(1));
  EXPECT_CLOSE(n->c(), T(4) / T(5), eps<T>(1));
  EXPECT_EQ(n->d(), T(-2));
  // Point (0, 0, 5): 4*5 - 10 = 10 unnormalised, distance 2 along the normal.
  EXPECT_EQ(dot_coord(*p, Vec3<T>(0, 0, 5)), T(10));
  EXPECT_CLOSE(signed_distance(*p, Vec3<T>(0, 0, 5)), T(2), eps<T>(2, T(2)));  // one sqrt, one division
  EXPECT_CLOSE(dot_coord(*n, Vec3<T>(0, 0, 5)), T(2), eps<T>(4, T(2)));       // rounded coefficients, 3 products
}

TYPED_TEST(PlaneTest, DotProducts) {
  using T = TypeParam;
  const Plane<T> p{Vec4<T>(1, 2, 3, 4)};
  EXPECT_EQ(dot_coord(p, Vec3<T>(1, 1, 1)), T(10));
  EXPECT_EQ(dot_normal(p, Vec3<T>(1, 1, 1)), T(6));
  EXPECT_EQ(dot(p, Vec4<T>(1, 1, 1, 0)), T(6));  // a direction ignores d
  EXPECT_EQ(dot(p, Vec4<T>(2, 2, 2, 2)), T(20));  // homogeneous: (2,2,2,2) is the point (1,1,1) scaled
}

TYPED_TEST(PlaneTest, DegenerateInputIsRefusedWithAReason) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  EXPECT_EQ(plane_from_coefficients<T>(0, 0, 0, 1).error(), Error::ZeroNormal);
  EXPECT_EQ(plane_from_coefficients<T>(nan, 1, 0, 0).error(), Error::NonFinite);
  EXPECT_EQ(plane_from_coefficients<T>(0, 1, 0, inf).error(), Error::NonFinite);
  EXPECT_EQ(plane_from_point_normal<T>(Vec3<T>(0, 0, 0), Vec3<T>(0, 0, 0)).error(), Error::ZeroNormal);
  EXPECT_EQ(plane_from_point_normal<T>(Vec3<T>(nan, 0, 0), Vec3<T>(0, 1, 0)).error(), Error::NonFinite);
  EXPECT_EQ(plane_from_points<T>(Vec3<T>(0, 0, 0), Vec3<T>(1, 1, 1), Vec3<T>(2, 2, 2)).error(), Error::CollinearPoints);
  EXPECT_EQ(plane_from_points<T>(Vec3<T>(1, 2, 3), Vec3<T>(1, 2, 3), Vec3<T>(1, 2, 3)).error(), Error::CollinearPoints);
  EXPECT_EQ(plane_from_points<T>(Vec3<T>(0, 0, 0), Vec3<T>(inf, 0, 0), Vec3<T>(0, 1, 0)).error(), Error::NonFinite);
  // A cross product that underflows to zero is as collinear as it gets in T.
  const T tiny = std::numeric_limits<T>::denorm_min();
  EXPECT_EQ(plane_from_points<T>(Vec3<T>(0, 0, 0), Vec3<T>(tiny, 0, 0), Vec3<T>(0, tiny, 0)).error(), Error::CollinearPoints);
  // A cross product that overflows is refused rather than returned as infinities.
  const T huge = std::numeric_limits<T>::max();
  EXPECT_EQ(plane_from_points<T>(Vec3<T>(0, 0, 0), Vec3<T>(huge, 0, 0), Vec3<T>(0, huge, 0)).error(), Error::NonFinite);
  EXPECT_EQ(normalize(Plane<T>{Vec4<T>(0, 0, 0, 3)}).error(), Error::ZeroNormal);
  EXPECT_EQ(normalize(Plane<T>{Vec4<T>(0, nan, 0, 3)}).error(), Error::NonFinite);
}

TYPED_TEST(PlaneTest, NormalizeSurvivesExtremeButFiniteCoefficients) {
  using T = TypeParam;
  const T big = std::numeric_limits<T>::max() / T(4);
  const auto n = normalize(Plane<T>{Vec4<T>(big, big, 0, 0)});  // |n|^2 overflows, |n| does not
  ASSERT_TRUE(n.ok()) << n.message();
  EXPECT_CLOSE(n->a(), std::sqrt(T(0.5)), eps<T>(4));  // sqrt and scaling inside Eigen's stable norm
}

}  // namespace
}  // namespace shadowref
