// mask_image.cpp — reading and writing 8-bit images with OpenImageIO, refusing what a comparison
// cannot judge (mask_image.hpp).
#include "shadowref/compare/mask_image.hpp"

#include <OpenImageIO/imageio.h>

#include <system_error>

namespace shadowref::compare {

Image8 read_image8(const std::filesystem::path& file, int channels) {
  const auto bad = [&](const std::string& what) {
    return CompareError(CompareError::Kind::BadInput, file.string() + ": " + what);
  };
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw bad("no such file");
  if (!std::filesystem::is_regular_file(file, ec)) throw bad("not a regular file");
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "not an image OpenImageIO can read";
    throw bad("cannot open: " + why);
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1) throw bad("not a 2D image");
  if (spec.nchannels != channels)
    throw bad("has " + std::to_string(spec.nchannels) + " channel(s), expected " + std::to_string(channels) +
              (channels == 1 ? " (8-bit grey: 255 lit, 0 shadowed, 128 no surface)" : ""));
  if (spec.format != OIIO::TypeDesc::UINT8) throw bad("pixel format " + std::string(spec.format.c_str()) + ", expected 8-bit unsigned");
  Image8 image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = channels;
  image.pixels.resize(image.pixel_count() * static_cast<std::size_t>(channels));
  // A truncated or corrupt PNG fails here (libpng reports the broken stream), not at open.
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, image.pixels.data())) {
    std::string why = in->geterror();
    if (why.empty()) why = "decoding failed";
    throw bad("cannot read pixels (truncated or corrupt?): " + why);
  }
  // OpenImageIO may defer an error until close (libpng's CRC check at the end of the stream).
  if (!in->close()) throw bad("cannot read pixels (truncated or corrupt?): " + in->geterror());
  return image;
}

void write_image8(const Image8& image, const std::filesystem::path& file) {
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) throw std::runtime_error("cannot create an image writer for " + file.string());
  const OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8);
  if (!out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) ||
      !out->close())
    throw std::runtime_error("cannot write " + file.string() + ": " + out->geterror());
}

}  // namespace shadowref::compare
