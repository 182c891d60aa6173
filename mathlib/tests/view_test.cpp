// Unit tests of shadowref/view.hpp: look_at against its definition and against GLM.
#include "shadowref/view.hpp"

#include <gtest/gtest.h>

#include <glm/ext/matrix_transform.hpp>
#include <limits>

#include "scalar_types.hpp"
#include "shadowref/glm_interop.hpp"

namespace shadowref {
namespace {

using test::eps;

template <class T>
class ViewTest : public ::testing::Test {};
TYPED_TEST_SUITE(ViewTest, test::Scalars);

template <class T>
Vec3<T> apply(const Mat4<T>& m, const Vec3<T>& p) {
  return (m * Vec4<T>(p.x(), p.y(), p.z(), T(1))).template head<3>();
}

TYPED_TEST(ViewTest, EyeGoesToTheOriginAndTargetDownTheViewAxis) {
  using T = TypeParam;
  const Vec3<T> eye(0, 4, 8), target(1, 0, -2), up(0, 1, 0);
  const T dist = (target - eye).norm();
  // Entries are unit-vector components times coordinates up to ~10: 32 ε relative to 10.
  const T tol = eps<T>(32, T(10));
  for (Handedness h : {Handedness::Right, Handedness::Left}) {
    const auto v = look_at(eye, target, up, h);
    ASSERT_TRUE(v.ok());
    EXPECT_TRUE((test::near_matrix(apply(*v, eye), Vec3<T>::Zero(), tol)));
    const T z = h == Handedness::Right ? -dist : dist;  // RH looks down −z, LH down +z
    EXPECT_TRUE((test::near_matrix(apply(*v, target), Vec3<T>(0, 0, z), tol)));
    // A point straight above the eye (world up) is above it in view space: y > 0, x = 0.
    const Vec3<T> above = apply(*v, Vec3<T>(eye + up));
    EXPECT_GT(above.y(), T(0));
    EXPECT_CLOSE(above.x(), T(0), tol);
    // The rotation part is orthonormal.
    const Mat3<T> r = v->template block<3, 3>(0, 0);
    EXPECT_TRUE((test::near_matrix(Mat3<T>(r * r.transpose()), Mat3<T>::Identity(), eps<T>(16))));
    // Both are proper rotations (det +1): a view matrix is rigid; the handedness of clip space
    // comes from the projection (which sign of z is "in front"), not from a mirror here.
    EXPECT_CLOSE(r.determinant(), T(1), eps<T>(16));
  }
}

TYPED_TEST(ViewTest, DegenerateInputIsRefusedWithAReason) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  EXPECT_EQ(look_at<T>(Vec3<T>(1, 2, 3), Vec3<T>(1, 2, 3), Vec3<T>(0, 1, 0)).error(), Error::EyeAtTarget);
  EXPECT_EQ(look_at<T>(Vec3<T>(0, 5, 0), Vec3<T>(0, 0, 0), Vec3<T>(0, 1, 0)).error(), Error::UpParallelToView);
  EXPECT_EQ(look_at<T>(Vec3<T>(0, 5, 0), Vec3<T>(0, 0, 0), Vec3<T>(0, 0, 0)).error(), Error::UpParallelToView);
  EXPECT_EQ(look_at<T>(Vec3<T>(nan, 5, 0), Vec3<T>(0, 0, 0), Vec3<T>(0, 1, 0)).error(), Error::NonFinite);
}

template <class T>
class ViewGlmTest : public ::testing::Test {};
TYPED_TEST_SUITE(ViewGlmTest, test::FloatAndDouble);

TYPED_TEST(ViewGlmTest, MatchesGlmLookAt) {
  using T = TypeParam;
  const glm::vec<3, T> e(0, 4, 8), c(1, 0, -2), u(0, 1, 0);
  const Vec3<T> eye(0, 4, 8), target(1, 0, -2), up(0, 1, 0);
  // GLM normalises with x · inversesqrt(x·x), we with x / sqrt(x·x): a few ulps apart on unit
  // vectors, times coordinates up to ~10 in the translation column.
  EXPECT_TRUE((test::near_matrix(*look_at(eye, target, up, Handedness::Right), from_glm(glm::lookAtRH(e, c, u)), eps<T>(16, T(10)))));
  EXPECT_TRUE((test::near_matrix(*look_at(eye, target, up, Handedness::Left), from_glm(glm::lookAtLH(e, c, u)), eps<T>(16, T(10)))));
}

}  // namespace
}  // namespace shadowref
