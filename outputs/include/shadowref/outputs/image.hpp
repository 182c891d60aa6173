// shadowref/outputs/image.hpp — the one 8-bit image type and the mask values of the output contract.
//
// Every mask (the reference's, our renderer's, an engine team's) answers, per pixel, "is the
// surface seen through this pixel centre lit by this light?" in one byte:
//   255 lit, 0 shadowed, 128 no surface (background). Any other value is an error, not rounded.
// Images are stored row 0 at the top, `channels` interleaved bytes per pixel (1: grey, 3: RGB).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace shadowref::outputs {

inline constexpr std::uint8_t kMaskLit = 255;
inline constexpr std::uint8_t kMaskShadowed = 0;
inline constexpr std::uint8_t kMaskNoSurface = 128;

// True for the three values a mask may hold.
constexpr bool is_mask_value(std::uint8_t v) { return v == kMaskLit || v == kMaskShadowed || v == kMaskNoSurface; }

// The one reading of a grey value as a mask value, the nearest of the three (a reference's mask, or a
// candidate's before its values are checked): below kMaskNoSurfaceFrom shadowed, from kMaskLitFrom
// lit, no surface between. As a class, the number of those thresholds passed: 0 shadowed, 1 no
// surface, 2 lit (branchless, so that loops over it vectorise; ordered as the values are).
inline constexpr std::uint8_t kMaskNoSurfaceFrom = 64;
inline constexpr std::uint8_t kMaskLitFrom = 192;
enum MaskClass : std::uint8_t { kClassShadowed = 0, kClassNoSurface = 1, kClassLit = 2 };
constexpr std::uint8_t mask_class(std::uint8_t v) {
  return static_cast<std::uint8_t>((v >= kMaskNoSurfaceFrom) + (v >= kMaskLitFrom));
}
constexpr std::uint8_t nearest_mask_value(std::uint8_t v) {
  constexpr std::uint8_t kValueOfClass[3] = {kMaskShadowed, kMaskNoSurface, kMaskLit};
  return kValueOfClass[mask_class(v)];
}

// A flag image (the reference's decided.png and covered.png): kFlagSet where the flag holds,
// kFlagClear elsewhere. The one reading, for every reader: set from 128 up. flag_bit is that as 0 / 1,
// branchless for vectorised loops.
inline constexpr std::uint8_t kFlagSet = 255;
inline constexpr std::uint8_t kFlagClear = 0;
constexpr std::uint8_t flag_bit(std::uint8_t v) { return static_cast<std::uint8_t>(v >> 7); }
constexpr bool is_flag_set(std::uint8_t v) { return flag_bit(v) != 0; }

struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<std::uint8_t> pixels;  // width · height · channels bytes

  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  std::uint8_t at(int x, int y, int c = 0) const {
    return pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                      static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)];
  }
};

}  // namespace shadowref::outputs
