// shadowref/compare/mask_image.hpp — 8-bit images as the comparison reads and writes them, through
// OpenImageIO, row 0 = the top row (DESIGN.md "Conventions").
//
// Reading refuses, with a one-line CompareError naming the file, everything a comparison cannot
// judge honestly: a missing file, a file OpenImageIO cannot open or decode (a truncated PNG), a
// channel count other than the one asked for, a pixel format other than 8-bit unsigned. Nothing
// is converted behind the caller's back (an RGB "grey" mask is refused, not averaged).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadowref::compare {

// What went wrong with the input of a comparison: the command line maps BadInput to exit 4 and
// SizeMismatch to exit 3 (DESIGN.md "The shadowref command").
class CompareError : public std::runtime_error {
 public:
  enum class Kind { BadInput, SizeMismatch };
  CompareError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

// An 8-bit image, `channels` interleaved bytes per pixel, row 0 at the top.
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<std::uint8_t> pixels;

  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  std::uint8_t at(int x, int y, int c = 0) const {
    return pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                      static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)];
  }
};

// Reads `file` as an 8-bit image with exactly `channels` channels. Throws CompareError(BadInput).
Image8 read_image8(const std::filesystem::path& file, int channels);

// Writes `image` (PNG when the name ends in .png). Throws std::runtime_error naming the file.
void write_image8(const Image8& image, const std::filesystem::path& file);

}  // namespace shadowref::compare
