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

// A grey value read as the nearest of the three (a reference's mask, or a candidate's before its
// values are checked): below kMaskNoSurfaceFrom shadowed, from kMaskLitFrom lit, no surface between.
inline constexpr std::uint8_t kMaskNoSurfaceFrom = 64;
inline constexpr std::uint8_t kMaskLitFrom = 192;
constexpr std::uint8_t nearest_mask_value(std::uint8_t v) {
  return v < kMaskNoSurfaceFrom ? kMaskShadowed : (v < kMaskLitFrom ? kMaskNoSurface : kMaskLit);
}

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
