// image_io.cpp — OpenImageIO reading and writing of the contract's images (image_io.hpp).
#include "shadowref/outputs/image_io.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"

namespace shadowref::outputs {
namespace {

// Images larger than this are refused before their pixels are allocated (the scene loader's own
// resolution limit is 16384 on a side).
constexpr std::size_t kMaxPixels = std::size_t{16384} * 16384;

// libpng, inside OpenImageIO, writes its own "libpng error: …" lines to stderr when a stream is
// truncated or corrupt; the command line promises ONE line naming the file, which we print from
// the exception. So stderr goes to /dev/null while a file is decoded. Process-wide, but only for
// the decode of one image, during which shadowref itself prints nothing.
class QuietStderr {
 public:
  QuietStderr() : saved_(::dup(2)) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    if (saved_ >= 0) {
      ::dup2(saved_, 2);
      ::close(saved_);
    }
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_;
};

// OpenImageIO queues one message per layer (ours, its format reader's, libpng's), one per line; the
// first says it, and the command line promises one line.
std::string first_line(std::string why, const char* if_empty) {
  if (why.empty()) return if_empty;
  const auto newline = why.find('\n');
  if (newline != std::string::npos) why.resize(newline);
  return why;
}

// OpenImageIO prints errors nobody retrieved when their holder dies (at exit for the global
// queue); we retrieve every error we act on and report it in our own one line.
void silence_uncaught_errors() {
  static const bool done = OIIO::attribute("oiio:print_uncaught_errors", 0);
  (void)done;
}

// The image is encoded in memory and written by write_file_atomically: a file appears whole or not at
// all, and a failed write says the system's reason ("No space left on device"), which OpenImageIO's
// own file writing does not pass on. An encoding failure is ours (exit 5), never the disk's.
void write_image(const std::filesystem::path& file, const OIIO::ImageSpec& spec, const void* data) {
  silence_uncaught_errors();
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);  // outlives the writer, which may flush into it when destroyed
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) throw std::runtime_error(file.string() + ": no image writer: " + first_line(OIIO::geterror(), "unknown format"));
  if (!out->set_ioproxy(&memory) || !out->open(file.string(), spec) || !out->write_image(spec.format, data) || !out->close())
    throw std::runtime_error(file.string() + ": cannot encode: " + first_line(out->geterror(), "encoding failed"));
  write_file_atomically(file, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

}  // namespace

Image8 read_image8(const std::filesystem::path& file, int channels) { return read_image8(file, channels, 0, 0); }

Image8 read_image8(const std::filesystem::path& file, int channels, int width, int height) {
  const auto bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, file.string() + ": " + what); };
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw bad("no such file");
  if (!std::filesystem::is_regular_file(file, ec)) throw bad("not a regular file");
  QuietStderr quiet;
  silence_uncaught_errors();
  // Only the reader of the file's own format (its extension): ImageInput::open falls back to every
  // other reader when that one fails, and OpenImageIO 2.4's RLA reader aborts the process on some
  // bytes (a fuzzed mask.png did, in RLAInput::seek_subimage), so a broken PNG must stay a PNG error.
  const std::string extension = file.extension().string();
  auto in = OIIO::ImageInput::create(extension.size() > 1 ? extension.substr(1) : file.string());
  OIIO::ImageSpec opened;
  if (!in || !in->open(file.string(), opened))
    throw bad("cannot open: " + first_line(in ? in->geterror() : OIIO::geterror(), "not an image OpenImageIO can read"));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1) throw bad("not a 2D image");
  if (static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) > kMaxPixels)
    throw bad(std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels: larger than 16384 x 16384");
  if (width > 0 && (spec.width != width || spec.height != height))
    throw InputError(InputError::Kind::SizeMismatch, file.string() + ": candidate is " + std::to_string(spec.width) + "x" +
                                                         std::to_string(spec.height) + ", reference is " + std::to_string(width) +
                                                         "x" + std::to_string(height));
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
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, image.pixels.data()))
    throw bad("cannot read pixels (truncated or corrupt?): " + first_line(in->geterror(), "decoding failed"));
  // OpenImageIO may defer an error until close (libpng's CRC check at the end of the stream).
  if (!in->close()) throw bad("cannot read pixels (truncated or corrupt?): " + first_line(in->geterror(), "closing failed"));
  return image;
}

std::vector<float> read_exr(const std::filesystem::path& file, int width, int height) {
  const auto bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, file.string() + ": " + what); };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw bad("no such file");
  QuietStderr quiet;
  silence_uncaught_errors();
  auto in = OIIO::ImageInput::create("exr");
  OIIO::ImageSpec opened;
  if (!in || !in->open(file.string(), opened))
    throw bad("cannot open: " + first_line(in ? in->geterror() : OIIO::geterror(), "not an OpenEXR file"));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != width || spec.height != height || spec.depth != 1 || spec.nchannels != 1)
    throw bad("is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " with " +
              std::to_string(spec.nchannels) + " channel(s), expected " + std::to_string(width) + "x" +
              std::to_string(height) + " with 1");
  std::vector<float> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, pixels.data()) || !in->close())
    throw bad("cannot read pixels: " + first_line(in->geterror(), "decoding failed"));
  return pixels;
}

void write_png(const Image8& image, const std::filesystem::path& file) {
  if (image.pixels.size() != image.pixel_count() * static_cast<std::size_t>(image.channels))
    throw std::logic_error(file.string() + ": image buffer does not match its size");
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8);
  // zlib level 1 instead of libpng's 6: a conformance run writes several images per case, and at
  // 1024² the level-6 deflate was a quarter of the run's CPU time (bench/README.md, "conform at
  // 1024²"); masks are large flat regions, which level 1 still compresses well.
  spec.attribute("png:compressionLevel", 1);
  write_image(file, spec, image.pixels.data());
}

void write_exr(int width, int height, const float* pixels, const std::filesystem::path& file) {
  OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"Y"};
  spec.attribute("compression", "zip");
  // OpenEXR output stamps the wall-clock time into the header unless DateTime is set; an empty
  // value suppresses it, so that two runs write byte-identical files (determinism is tested).
  spec.attribute("DateTime", "");
  write_image(file, spec, pixels);
}

}  // namespace shadowref::outputs
