// png_codec.hpp — PNG encoding and decoding with libpng, inside the outputs library; image_io.cpp
// keeps every check and message.
//
// Why not through the image codec module (image_codec.hpp) like every other format: a conformance
// case reads and writes only PNGs, and loading OpenImageIO's 260 libraries cost each such process
// 0.3 s, most of a case's time; libpng is one small library, loaded with the process.
//
// Decoding does what OpenImageIO's PNG reader does (png_set_expand: 1-, 2- and 4-bit grey to 8 bits,
// a palette to RGB, a tRNS chunk to an alpha channel; 16-bit samples stay 16-bit) and nothing more:
// no gamma or colour-space conversion, so the samples are the file's own, whatever its gAMA, sRGB
// or iCCP chunks say.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "shadowref/outputs/image.hpp"

namespace shadowref::outputs::png {

// `image` (1 to 4 channels: grey, grey + alpha, RGB, RGBA; row 0 at the top) as a PNG stream: no row filters and a fast deflate
// (PNG_IMAGE_FLAG_FAST), no colour-space chunk. Throws std::runtime_error with libpng's reason.
std::string encode(const Image8& image);

// An opened PNG file: the header on construction, the pixels with read(). A failure (the file
// cannot be opened, is not a PNG, is truncated or corrupt) leaves why() non-empty: libpng's own
// one-line reason, or the system's.
class Reader {
 public:
  explicit Reader(const std::filesystem::path& file);
  // The same over PNG bytes in memory (an image embedded in a glTF file), which must outlive the
  // reader.
  struct FromMemory {};
  Reader(FromMemory, const std::string& bytes);
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  const std::string& why() const { return why_; }
  // After expansion (see above): channels 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA; bit_depth 8 or 16.
  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  int bit_depth() const { return bit_depth_; }
  // Decodes every row into `pixels` (height × width × channels samples of bit_depth, top row first)
  // and the chunks after them; false with why() filled when the stream is broken.
  bool read(std::uint8_t* pixels);

  struct State;  // libpng's structures and the message buffer its error handler fills (png_codec.cpp)

 private:
  void open();  // the header from state_->file, or why_

  State* state_ = nullptr;
  std::string why_;
  int width_ = 0, height_ = 0, channels_ = 0, bit_depth_ = 0;
};

}  // namespace shadowref::outputs::png
