// Unit tests of shadowref/transform_points.hpp: every path (scalar, SSE2, and AVX2 + FMA where the
// CPU has it) against the product computed in double, odd counts, in place, and nothing at all.
#include "shadowref/transform_points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "shadowref/shadow_matrix.hpp"

namespace shadowref {
namespace {

Mat4<float> a_shadow_matrix() {
  const auto plane = plane_from_coefficients(0.1f, 1.0f, 0.2f, -0.5f).value();
  return shadow_matrix(plane, Vec4<float>(2.0f, 6.0f, 1.0f, 1.0f)).value();
}

std::vector<float> random_points(std::size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  std::vector<float> p(4 * n);
  for (std::size_t i = 0; i < n; ++i) p[4 * i] = u(rng), p[4 * i + 1] = u(rng), p[4 * i + 2] = u(rng), p[4 * i + 3] = 1.0f;
  return p;
}

// Each output component against the double product of the same floats. Tolerance: a 4-term dot
// product in float, however its sums are ordered or fused, is within 4 ε Σ|m_rc v_c| of the exact
// value (Higham, Accuracy and Stability, §3.1): the bound, not a guess.
void expect_product(const Mat4<float>& m, const std::vector<float>& in, const std::vector<float>& out) {
  ASSERT_EQ(in.size(), out.size());
  for (std::size_t i = 0; i < in.size() / 4; ++i)
    for (int r = 0; r < 4; ++r) {
      double exact = 0, scale = 0;
      for (int c = 0; c < 4; ++c) {
        exact += double(m(r, c)) * double(in[4 * i + c]);
        scale += std::abs(double(m(r, c)) * double(in[4 * i + c]));
      }
      ASSERT_NEAR(out[4 * i + r], exact, 4 * 1.1920929e-7 * scale) << "point " << i << " row " << r;
    }
}

using Path = void (*)(const float (&)[16], const float*, float*, std::size_t);

TEST(TransformPoints, TheDispatchedPathIsTheProduct) {
  const Mat4<float> m = a_shadow_matrix();
  for (std::size_t n : {0u, 1u, 2u, 3u, 17u, 1000u}) {
    const auto in = random_points(n);
    std::vector<float> out(in.size(), -1.0f);
    transform_points(m, in.data(), out.data(), n);
    expect_product(m, in, out);
  }
}

TEST(TransformPoints, EveryPathIsTheProduct) {
  const Mat4<float> m = a_shadow_matrix();
  float cols[16];
  detail::matrix_columns(m, cols);
  const auto in = random_points(33);  // odd: the AVX2 path's single last point
  std::vector<float> out(in.size());
  detail::transform_points_scalar(cols, in.data(), out.data(), 0, 33);
  expect_product(m, in, out);
#ifdef SHADOWREF_TRANSFORM_POINTS_X86
  std::fill(out.begin(), out.end(), -1.0f);
  detail::transform_points_sse2(cols, in.data(), out.data(), 33);
  expect_product(m, in, out);
  if (!cpu_has_avx2_fma()) GTEST_SKIP() << "this CPU has no AVX2 + FMA: that path was not run";
  std::fill(out.begin(), out.end(), -1.0f);
  detail::transform_points_avx2(cols, in.data(), out.data(), 33);
  expect_product(m, in, out);
#endif
}

TEST(TransformPoints, InPlaceIsTheProduct) {
  const Mat4<float> m = a_shadow_matrix();
  const auto in = random_points(9);
  std::vector<float> buf = in;
  transform_points(m, buf.data(), buf.data(), 9);
  expect_product(m, in, buf);
}

// The shadow matrix's own property through the batch: every point lands on the plane after the
// divide (a transform that dropped a column would not).
TEST(TransformPoints, ShadowMatrixPointsLandOnThePlane) {
  const auto plane = plane_from_coefficients(0.0f, 1.0f, 0.0f, 0.0f).value();
  const Mat4<float> s = shadow_matrix(plane, Vec4<float>(2.0f, 30.0f, 1.0f, 1.0f)).value();
  auto in = random_points(64);
  for (std::size_t i = 0; i < 64; ++i) in[4 * i + 1] = std::abs(in[4 * i + 1]);  // below the light
  std::vector<float> out(in.size());
  transform_points(s, in.data(), out.data(), 64);
  for (std::size_t i = 0; i < 64; ++i) EXPECT_NEAR(out[4 * i + 1] / out[4 * i + 3], 0.0f, 1e-5f) << "point " << i;
}

}  // namespace
}  // namespace shadowref
