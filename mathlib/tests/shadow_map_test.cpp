// Unit tests of shadowref/shadow_map.hpp: the bias matrix maps the light's NDC cube to texture space.
#include "shadowref/shadow_map.hpp"

#include <gtest/gtest.h>

#include "scalar_types.hpp"

namespace shadowref {
namespace {

template <class T>
class ShadowMapTest : public ::testing::Test {};
TYPED_TEST_SUITE(ShadowMapTest, test::Scalars);

template <class T>
Vec3<T> apply(const Mat4<T>& m, T x, T y, T z) {
  return (m * Vec4<T>(x, y, z, 1)).template head<3>();
}

TYPED_TEST(ShadowMapTest, NegOneToOneMapsTheNdcCubeOntoTheUnitCube) {
  using T = TypeParam;
  const Mat4<T> b = shadow_bias_matrix<T>(DepthRange::NegOneToOne);
  EXPECT_EQ(apply<T>(b, -1, -1, -1), Vec3<T>(0, 0, 0));  // halves and sums of ±1: exact
  EXPECT_EQ(apply<T>(b, 1, 1, 1), Vec3<T>(1, 1, 1));
  EXPECT_EQ(apply<T>(b, 0, 0, 0), Vec3<T>(T(0.5), T(0.5), T(0.5)));
}

TYPED_TEST(ShadowMapTest, ZeroToOneLeavesDepthAlone) {
  using T = TypeParam;
  const Mat4<T> b = shadow_bias_matrix<T>(DepthRange::ZeroToOne);
  EXPECT_EQ(apply<T>(b, -1, -1, 0), Vec3<T>(0, 0, 0));
  EXPECT_EQ(apply<T>(b, 1, 1, 1), Vec3<T>(1, 1, 1));
  EXPECT_EQ(apply<T>(b, 0, 0, T(0.25)), Vec3<T>(T(0.5), T(0.5), T(0.25)));
}

TYPED_TEST(ShadowMapTest, TopLeftOriginFlipsTheVerticalTextureCoordinate) {
  using T = TypeParam;
  const Mat4<T> b = shadow_bias_matrix<T>(DepthRange::ZeroToOne, TextureOrigin::TopLeft);
  EXPECT_EQ(apply<T>(b, -1, 1, 0), Vec3<T>(0, 0, 0));  // NDC top-left is texel row 0
  EXPECT_EQ(apply<T>(b, 1, -1, 1), Vec3<T>(1, 1, 1));
}

TYPED_TEST(ShadowMapTest, ComposesWithHomogeneousClipCoordinates) {
  using T = TypeParam;
  // B applies before the divide: B · clip then dividing by w equals B applied to NDC, because B
  // leaves w alone (last row (0, 0, 0, 1)).
  const Mat4<T> b = shadow_bias_matrix<T>(DepthRange::NegOneToOne);
  const Vec4<T> clip(T(-1), T(2), T(3), T(4));  // NDC (-0.25, 0.5, 0.75)
  const Vec4<T> tex = b * clip;
  EXPECT_EQ(tex.w(), T(4));
  EXPECT_EQ(Vec3<T>(tex.template head<3>() / tex.w()), Vec3<T>(T(0.375), T(0.75), T(0.875)));
}

}  // namespace
}  // namespace shadowref
