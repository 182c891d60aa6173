// image_codec.cpp — the OpenImageIO side of the contract's images (image_codec.hpp says why it is a
// module of its own): open and read with the file's own format's reader, encode OpenEXR in memory.
#include "image_codec.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

void fill(char* error, std::size_t size, const std::string& what) {
  if (size == 0) return;
  const std::size_t n = std::min(size - 1, what.size());
  std::memcpy(error, what.data(), n);
  error[n] = '\0';
}

OIIO::TypeDesc type_of(int type) { return type == kShadowrefFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8; }

void* open_image(const char* file, const char* format, ShadowrefImageHeader* header, char* error, std::size_t error_size) {
  // Only the reader of the file's own format: ImageInput::open falls back to every other reader
  // when that one fails, and OpenImageIO 2.4's RLA reader aborts the process on some bytes (a
  // fuzzed mask.png did, in RLAInput::seek_subimage), so a broken PNG must stay a PNG error.
  auto in = OIIO::ImageInput::create(format);
  OIIO::ImageSpec opened;
  if (!in || !in->open(file, opened)) {
    fill(error, error_size, in ? in->geterror() : OIIO::geterror());
    return nullptr;
  }
  const OIIO::ImageSpec& spec = in->spec();
  header->width = spec.width;
  header->height = spec.height;
  header->depth = spec.depth;
  header->channels = spec.nchannels;
  header->is_uint8 = spec.format == OIIO::TypeDesc::UINT8;
  fill(header->format, sizeof header->format, spec.format.c_str());
  return in.release();
}

int read_image(void* reader, int channels, int type, void* pixels, char* error, std::size_t error_size) {
  auto* in = static_cast<OIIO::ImageInput*>(reader);
  // A truncated or corrupt PNG fails here (libpng reports the broken stream), not at open; and
  // OpenImageIO may defer an error until close (libpng's CRC check at the end of the stream).
  if (!in->read_image(0, 0, 0, channels, type_of(type), pixels) || !in->close()) {
    fill(error, error_size, in->geterror());
    return 1;
  }
  return 0;
}

void free_reader(void* reader) { delete static_cast<OIIO::ImageInput*>(reader); }

int encode_exr(const char* file, int width, int height, const float* pixels, const char* channel,
               void (*sink)(void*, const void*, std::size_t), void* context, char* error, std::size_t error_size) {
  OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {channel};
  spec.attribute("compression", "zip");
  // OpenEXR output stamps the wall-clock time into the header unless DateTime is set; an empty
  // value suppresses it, so that two runs write byte-identical files.
  spec.attribute("DateTime", "");
  std::vector<unsigned char> encoded;
  {
    OIIO::Filesystem::IOVecOutput memory(encoded);  // outlives the writer, which may flush into it when destroyed
    auto out = OIIO::ImageOutput::create("exr");
    if (!out || !out->set_ioproxy(&memory) || !out->open(file, spec) || !out->write_image(spec.format, pixels) ||
        !out->close()) {
      fill(error, error_size, out ? out->geterror() : OIIO::geterror());
      return 1;
    }
  }
  sink(context, encoded.data(), encoded.size());
  return 0;
}

constexpr ShadowrefImageCodec kCodec{kShadowrefImageCodecVersion, open_image, read_image, free_reader, encode_exr};

}  // namespace

extern "C" __attribute__((visibility("default"))) const ShadowrefImageCodec* shadowref_image_codec() {
  // OpenImageIO prints errors nobody retrieved when their holder dies (at exit for the global
  // queue); every error we act on is retrieved and reported in shadowref's own one line.
  static const bool silenced = OIIO::attribute("oiio:print_uncaught_errors", 0);
  (void)silenced;
  return &kCodec;
}
