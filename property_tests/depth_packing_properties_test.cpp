// depth_packing_properties_test.cpp — RGBA8 depth packing (shadowref/depth_packing.hpp), in float
// and double: the round trip stays within the packing's resolution, and packing keeps order.
#include "generators.hpp"
#include "property_support.hpp"
#include "shadowref/depth_packing.hpp"

namespace shadowref::prop {
namespace {

// Depths in [0, 1] at every scale of the 24-bit grid (uniform, near 0, near 1, exactly on and half
// a step off the grid), plus values outside [0, 1] that must clamp.
template <class T>
rc::Gen<T> depth() {
  const double step = 1.0 / kPackedDepthMax;
  return rc::gen::map(
      rc::gen::oneOf(gen::uniform(0, 1), rc::gen::map(gen::power_of_ten(-9, 0), [](double d) { return d; }),
                     rc::gen::map(gen::power_of_ten(-9, 0), [](double d) { return 1 - d; }),
                     rc::gen::map(rc::gen::inRange<std::uint32_t>(0, kPackedDepthMax + 1),
                                  [step](std::uint32_t q) { return q * step; }),
                     rc::gen::map(rc::gen::inRange<std::uint32_t>(0, kPackedDepthMax),
                                  [step](std::uint32_t q) { return (q + 0.5) * step; }),
                     gen::uniform(-2, 3)),
      [](double d) { return static_cast<T>(d); });
}

template <class T>
class DepthPackingProperties : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(DepthPackingProperties, Scalars);

// unpack(pack(d)) is within half a step of clamp(d, 0, 1), plus the rounding of the one multiply
// d · (2^24 − 1) (half an ulp of the product, i.e. ε/2 relative, over the 2^24 − 1 steps).
TYPED_TEST(DepthPackingProperties, round_trip_is_within_the_resolution) {
  using T = TypeParam;
  check_property([] {
    const T d = *depth<T>();
    const auto bytes = pack_depth_rgba8(d);
    RC_ASSERT(bytes[3] == 255);
    const Wide back = unpack_depth_rgba8_value<Wide>(bytes);
    const Wide clamped = std::clamp<Wide>(d, 0, 1);
    const Wide step = Wide(1) / kPackedDepthMax;
    const Wide tol = step / 2 + rounding<T>(1, clamped) + rounding<Wide>(4, 1);
    RC_LOG() << "d = " << d << " bytes " << int{bytes[0]} << " " << int{bytes[1]} << " " << int{bytes[2]} << " back "
             << static_cast<double>(back) << "\n";
    RC_ASSERT(std::abs(back - clamped) <= tol);
    RC_ASSERT(unpack_depth_rgba8(bytes) == quantize_depth(d));
  });
}

// d1 <= d2 implies packed(d1) <= packed(d2): a nearer surface never packs to a farther value.
TYPED_TEST(DepthPackingProperties, packing_keeps_order) {
  using T = TypeParam;
  check_property([] {
    T d1 = *depth<T>(), d2 = *depth<T>();
    if (d2 < d1) std::swap(d1, d2);
    const std::uint32_t q1 = unpack_depth_rgba8(pack_depth_rgba8(d1)), q2 = unpack_depth_rgba8(pack_depth_rgba8(d2));
    RC_LOG() << "d1 = " << d1 << " -> " << q1 << ", d2 = " << d2 << " -> " << q2 << "\n";
    RC_ASSERT(q1 <= q2);
  });
}

// Every 24-bit value round-trips exactly through its depth.
TYPED_TEST(DepthPackingProperties, every_quantised_value_round_trips) {
  using T = TypeParam;
  check_property([] {
    const std::uint32_t q = *rc::gen::inRange<std::uint32_t>(0, kPackedDepthMax + 1);
    RC_ASSERT(quantize_depth(depth_from_quantized<T>(q)) == q);
    RC_ASSERT(unpack_depth_rgba8(pack_quantized_depth_rgba8(q)) == q);
  });
}

}  // namespace
}  // namespace shadowref::prop
