// Tests of shadowref/depth_packing.hpp: exact endpoints, monotonicity, round trips.
#include "shadowref/depth_packing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace shadowref {
namespace {

template <class T>
class DepthPacking : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(DepthPacking, Scalars);

TYPED_TEST(DepthPacking, EndpointsAndClamping) {
  using T = TypeParam;
  EXPECT_EQ(quantize_depth(T(0)), 0u);
  EXPECT_EQ(quantize_depth(T(1)), kPackedDepthMax);
  EXPECT_EQ(quantize_depth(T(-0.5)), 0u);
  EXPECT_EQ(quantize_depth(T(2)), kPackedDepthMax);
  EXPECT_EQ(quantize_depth(-std::numeric_limits<T>::infinity()), 0u);
  EXPECT_EQ(quantize_depth(std::numeric_limits<T>::infinity()), kPackedDepthMax);
  // NaN packs as "far": nothing occludes (documented degenerate behaviour).
  EXPECT_EQ(quantize_depth(std::numeric_limits<T>::quiet_NaN()), kPackedDepthMax);
  const auto one = pack_depth_rgba8(T(1));
  EXPECT_EQ(one[0], 255);
  EXPECT_EQ(one[1], 255);
  EXPECT_EQ(one[2], 255);
  EXPECT_EQ(one[3], 255);
  const auto zero = pack_depth_rgba8(T(0));
  EXPECT_EQ(zero[0], 0);
  EXPECT_EQ(zero[1], 0);
  EXPECT_EQ(zero[2], 0);
  EXPECT_EQ(zero[3], 255);
}

TYPED_TEST(DepthPacking, ByteOrderIsMostSignificantFirst) {
  const auto b = pack_quantized_depth_rgba8(0x123456u);
  EXPECT_EQ(b[0], 0x12);
  EXPECT_EQ(b[1], 0x34);
  EXPECT_EQ(b[2], 0x56);
  EXPECT_EQ(unpack_depth_rgba8(b), 0x123456u);
}

TYPED_TEST(DepthPacking, EveryQuantisedValueRoundTrips) {
  using T = TypeParam;
  // All 2^24 values: cheap (a few tens of ms) and leaves no gap for a wrong shift to hide in.
  for (std::uint32_t q = 0; q <= kPackedDepthMax; ++q) {
    const T d = depth_from_quantized<T>(q);
    const std::uint32_t back = unpack_depth_rgba8(pack_depth_rgba8(d));
    if (back != q) {
      ADD_FAILURE() << "q = " << q << " -> d = " << d << " -> " << back;
      return;
    }
  }
}

TYPED_TEST(DepthPacking, RoundTripErrorIsHalfAStep) {
  using T = TypeParam;
  std::mt19937 rng(20240607u);
  std::uniform_real_distribution<T> uni(T(0), T(1));
  // Half a quantisation step, plus the rounding of d · (2^24 − 1) (one ulp of a value below
  // 2^24, i.e. at most 2^24 · eps / 2^24 = eps in units of d).
  const T step = T(1) / static_cast<T>(kPackedDepthMax);
  const T tol = step / T(2) + std::numeric_limits<T>::epsilon();
  for (int i = 0; i < 200000; ++i) {
    const T d = uni(rng);
    const T back = unpack_depth_rgba8_value<T>(pack_depth_rgba8(d));
    ASSERT_LE(std::abs(back - d), tol) << "d = " << d;
  }
}

TYPED_TEST(DepthPacking, MonotonicAcrossAdjacentScalars) {
  using T = TypeParam;
  // Walk neighbouring representable values (nextafter) around many points, including the
  // points where a byte carries over, and check that q never decreases.
  std::mt19937 rng(7u);
  std::uniform_real_distribution<T> uni(T(0), T(1));
  for (int i = 0; i < 2000; ++i) {
    T d = i < 256 ? depth_from_quantized<T>(static_cast<std::uint32_t>(i) << 16) : uni(rng);
    std::uint32_t prev = quantize_depth(d);
    for (int k = 0; k < 64; ++k) {
      const T next = std::nextafter(d, T(2));
      const std::uint32_t q = quantize_depth(next);
      ASSERT_GE(q, prev) << "d = " << d << " next = " << next;
      prev = q;
      d = next;
    }
  }
  // And in coarse strides over the whole range.
  std::uint32_t prev = 0;
  for (int i = 0; i <= 100000; ++i) {
    const std::uint32_t q = quantize_depth(static_cast<T>(i) / T(100000));
    ASSERT_GE(q, prev);
    prev = q;
  }
  EXPECT_EQ(prev, kPackedDepthMax);
}

TYPED_TEST(DepthPacking, DistinctStepsStayDistinct) {
  using T = TypeParam;
  // Two depths one quantisation step apart never pack to the same bytes: the packing keeps the
  // full 24 bits (a lossy packing would fail here).
  for (std::uint32_t q = 0; q + 1 <= kPackedDepthMax; q += 4099u) {
    const auto a = pack_depth_rgba8(depth_from_quantized<T>(q));
    const auto b = pack_depth_rgba8(depth_from_quantized<T>(q + 1));
    ASSERT_LT(unpack_depth_rgba8(a), unpack_depth_rgba8(b)) << q;
  }
}

}  // namespace
}  // namespace shadowref
