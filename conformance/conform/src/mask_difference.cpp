// mask_difference.cpp — two candidate masks of one light compared byte by byte (mask_difference.hpp).
#include "shadowref/conform/mask_difference.hpp"

#include <stdexcept>
#include <string>

namespace shadowref::conform {
namespace {

void check_comparable(const outputs::Image8& a, const outputs::Image8& b) {
  if (a.width != b.width || a.height != b.height || a.channels != 1 || b.channels != 1)
    throw std::invalid_argument("mask difference of " + std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                                std::to_string(b.width) + "x" + std::to_string(b.height) + " grey masks");
}

// Where the masks agree: the error image's background (by mask class), so both pictures read alike.
constexpr outputs::Rgb kDimmed[3] = {outputs::kDimmedShadowed, outputs::kDimmedNoSurface, outputs::kDimmedLit};

// The legend row of a pixel where the bytes differ.
const MaskDifferenceClass& class_of(std::uint8_t va, std::uint8_t vb) {
  const std::uint8_t ca = outputs::mask_class(va), cb = outputs::mask_class(vb);
  if (ca == cb) return kMaskDifferenceClasses[3];
  if (ca == outputs::kClassNoSurface || cb == outputs::kClassNoSurface) return kMaskDifferenceClasses[2];
  return cb == outputs::kClassShadowed ? kMaskDifferenceClasses[0] : kMaskDifferenceClasses[1];
}

}  // namespace

std::size_t count_differing_pixels(const outputs::Image8& a, const outputs::Image8& b) {
  check_comparable(a, b);
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) n += a.pixels[i] != b.pixels[i];
  return n;
}

outputs::Image8 paint_mask_difference(const outputs::Image8& a, const outputs::Image8& b) {
  check_comparable(a, b);
  outputs::Image8 out;
  out.width = a.width;
  out.height = a.height;
  out.channels = 3;
  out.pixels.resize(a.pixel_count() * 3);
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    std::uint8_t* px = &out.pixels[3 * i];
    const outputs::Rgb& c = a.pixels[i] == b.pixels[i] ? kDimmed[outputs::mask_class(a.pixels[i])]
                                                       : class_of(a.pixels[i], b.pixels[i]).colour;
    px[0] = c[0];
    px[1] = c[1];
    px[2] = c[2];
  }
  return out;
}

}  // namespace shadowref::conform
