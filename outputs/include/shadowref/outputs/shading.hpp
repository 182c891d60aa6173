// shadowref/outputs/shading.hpp — the lighting model of shaded.png, the same for every producer,
// so that the reference's picture and a candidate's, side by side in the report, differ only where
// their shadows do.
//
// Flat Lambert with face normals (turned toward the viewer): colour = albedo · (kAmbient + Σ_i
// kDirect / N · max(0, n · l_i) · visible_i · cone_i) over the N lights, where a spot light's cone is
// a hard cut-off; kBackground where there is no surface. Computed in linear light and stored as 8-bit
// sRGB (IEC 61966-2-1), which is what a PNG viewer assumes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace shadowref::outputs {

inline constexpr double kAmbient = 0.1;
inline constexpr double kDirect = 0.9;  // shared by the lights: kAmbient + kDirect = 1 for a fully lit, facing surface
inline constexpr std::array<double, 3> kBackground{0.05, 0.06, 0.09};

// Linear [0, 1] (clamped) → the 8-bit sRGB code.
inline std::uint8_t encode_srgb8(double linear) {
  const double x = std::clamp(linear, 0.0, 1.0);
  const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(s * 255));
}

// For producers that render in 8-bit linear (the OpenGL renderer's RGBA8 target): the sRGB code of
// each linear byte value.
inline const std::array<std::uint8_t, 256>& srgb8_from_linear8() {
  static const std::array<std::uint8_t, 256> table = [] {
    std::array<std::uint8_t, 256> t{};
    for (int i = 0; i < 256; ++i) t[static_cast<std::size_t>(i)] = encode_srgb8(i / 255.0);
    return t;
  }();
  return table;
}

}  // namespace shadowref::outputs
