// shadowref/depth_packing.hpp — a depth value in [0, 1] packed into the R, G, B bytes of an RGBA8
// colour, the shadow-map storage of hardware without depth textures (GeForce 2 / OpenGL ES 2 era).
//
// Packing is 24-bit fixed point, most significant byte first:
//     q = roundEven(clamp(d, 0, 1) · (2²⁴ − 1)),   R = q >> 16,  G = (q >> 8) & 255,  B = q & 255,  A = 255
// and unpacking rebuilds q from the bytes; a shadow test compares the two q's as integers.
// Why fixed point and not the classic `fract(d · (1, 255, 255², 255³))` chain: that chain loses
// bits to float rounding and breaks at d = 1 (fract(1) = 0), so it is neither exact nor monotonic;
// here every step is one correctly rounded multiply, an exact rounding and integer shifts, so that
// the GLSL mirror (renderer/shaders.cpp: `pack_depth_rgba8`, `unpack_depth_rgba8`)
// gives the very same bytes as these functions with T = float. The packed 24 bits equal the
// precision of a DEPTH_COMPONENT24 buffer.
//
// Properties (tested in depth_packing_test.cpp): q is non-decreasing in d (monotonic: a nearer
// surface never packs to a larger value); unpack(pack(d)) is within half a step (2⁻²⁴ ≈ 6e-8)
// of d plus the rounding of the multiply; every q in [0, 2²⁴ − 1] round-trips exactly
// (pack(depth_from_quantized(q)) = q); d ≤ 0 → q = 0, d ≥ 1 → q = 2²⁴ − 1.
// Degenerate input: NaN packs as the far value 2²⁴ − 1 ("nothing occludes"), never as garbage.
// (GLSL's clamp of a NaN is undefined; the renderer never produces one.) Cost: O(1).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "shadowref/conventions.hpp"

namespace shadowref {

// The largest quantised depth: 2^24 − 1, exactly representable in float.
inline constexpr std::uint32_t kPackedDepthMax = (1u << 24) - 1u;

// The quantised depth q of d ∈ [0, 1] (clamped; NaN → kPackedDepthMax). Uses the current rounding
// mode's nearbyint, i.e. round-half-to-even like GLSL's roundEven under the default mode.
template <class T>
std::uint32_t quantize_depth(T d) {
  if (std::isnan(d)) return kPackedDepthMax;
  if (!(d > T(0))) return 0u;
  if (!(d < T(1))) return kPackedDepthMax;
  const T scaled = d * static_cast<T>(kPackedDepthMax);  // one correctly rounded multiply
  return static_cast<std::uint32_t>(std::nearbyint(scaled));
}

// The depth a quantised value stands for: q / (2^24 − 1). q above the maximum is clamped.
template <class T>
T depth_from_quantized(std::uint32_t q) {
  if (q > kPackedDepthMax) q = kPackedDepthMax;
  return static_cast<T>(q) / static_cast<T>(kPackedDepthMax);
}

// The RGBA8 bytes of a quantised depth: R most significant, A = 255 (so that an 8-bit alpha test
// or blend never discards the texel).
inline std::array<std::uint8_t, 4> pack_quantized_depth_rgba8(std::uint32_t q) {
  if (q > kPackedDepthMax) q = kPackedDepthMax;
  return {static_cast<std::uint8_t>(q >> 16), static_cast<std::uint8_t>((q >> 8) & 0xFFu),
          static_cast<std::uint8_t>(q & 0xFFu), std::uint8_t{255}};
}

// The RGBA8 bytes of a depth d ∈ [0, 1] (see the header comment for clamping and NaN).
template <class T>
std::array<std::uint8_t, 4> pack_depth_rgba8(T d) {
  return pack_quantized_depth_rgba8(quantize_depth(d));
}

// The quantised depth stored in RGBA8 bytes (alpha is ignored). Exact inverse of the packing.
inline std::uint32_t unpack_depth_rgba8(const std::array<std::uint8_t, 4>& rgba) {
  return (std::uint32_t{rgba[0]} << 16) | (std::uint32_t{rgba[1]} << 8) | std::uint32_t{rgba[2]};
}

// The depth stored in RGBA8 bytes, as a scalar in [0, 1].
template <class T>
T unpack_depth_rgba8_value(const std::array<std::uint8_t, 4>& rgba) {
  return depth_from_quantized<T>(unpack_depth_rgba8(rgba));
}

}  // namespace shadowref
