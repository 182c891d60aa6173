// image_io.cpp — the contract's images (image_io.hpp): every check and message here; PNG decoded
// and encoded by libpng (png_codec.hpp), every other format by OpenImageIO in the image codec module
// (image_codec.hpp), loaded on first use.
#include "shadowref/outputs/image_io.hpp"

#include <atomic>

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "image_codec.hpp"
#include "png_codec.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"

namespace shadowref::outputs {
namespace {

// Images larger than this are refused before their pixels are allocated (the scene loader's own
// resolution limit is 16384 on a side).
constexpr std::size_t kMaxPixels = std::size_t{16384} * 16384;

// The module, where an installed shadowref has it (beside bin/, SHADOWREF_IMAGE_CODEC_FROM_BIN) and
// where this build tree has it (SHADOWREF_IMAGE_CODEC_BUILT). The installed place comes first, so
// that an installed binary never depends on the tree it was built in.
const ShadowrefImageCodec& codec() {
  static const ShadowrefImageCodec* loaded = [] {
    std::string tried;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    std::vector<std::filesystem::path> places;
    if (!ec) places.push_back(exe.parent_path() / SHADOWREF_IMAGE_CODEC_FROM_BIN);
    places.emplace_back(SHADOWREF_IMAGE_CODEC_BUILT);
    for (const std::filesystem::path& place : places) {
      if (!std::filesystem::exists(place, ec)) {
        tried += (tried.empty() ? "" : "; ") + place.string() + ": no such file";
        continue;
      }
      void* handle = ::dlopen(place.c_str(), RTLD_LAZY | RTLD_LOCAL);
      if (!handle) {
        const char* why = ::dlerror();
        tried += (tried.empty() ? "" : "; ") + std::string(why ? why : place.string() + ": dlopen failed");
        continue;
      }
      const auto entry = reinterpret_cast<ShadowrefImageCodecEntry>(::dlsym(handle, "shadowref_image_codec"));
      const ShadowrefImageCodec* c = entry ? entry() : nullptr;
      if (c && c->version == kShadowrefImageCodecVersion) return c;
      tried += (tried.empty() ? "" : "; ") + place.string() + ": not this version's image codec";
    }
    throw std::runtime_error("cannot load shadowref's image codec (libshadowref_image_codec.so, which reads and writes "
                             "images with OpenImageIO): " + tried);
  }();
  return *loaded;
}

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

constexpr std::size_t kErrorSize = 1024;

// An opened image: its header, and the reader the module frees.
struct Opened {
  ShadowrefImageHeader header{};
  std::unique_ptr<void, void (*)(void*)> reader{nullptr, +[](void*) {}};
};

// Opens `file` with the reader of `format`; throws bad(cannot open: …) with `if_empty` when the
// reader says nothing.
template <class Bad>
Opened open_image(const ShadowrefImageCodec& c, const std::filesystem::path& file, const std::string& format,
                  const char* if_empty, const Bad& bad) {
  Opened o;
  char error[kErrorSize] = "";
  void* reader = c.open(file.c_str(), format.c_str(), &o.header, error, sizeof error);
  if (!reader) throw bad("cannot open: " + first_line(error, if_empty));
  o.reader = std::unique_ptr<void, void (*)(void*)>(reader, c.free_reader);
  return o;
}

// An EXR is encoded in memory by the codec module and written by write_file_atomically, as a PNG is:
// a file appears whole or not at all, and a failed write says the system's reason ("No space left on
// device"), which OpenImageIO's own file writing does not pass on. An encoding failure is ours (exit
// 5), never the disk's.
void write_exr_image(const std::filesystem::path& file, int width, int height, const float* pixels, const char* channel) {
  const ShadowrefImageCodec& c = codec();
  std::string encoded;
  char error[kErrorSize] = "";
  const auto sink = +[](void* context, const void* bytes, std::size_t size) {
    static_cast<std::string*>(context)->assign(static_cast<const char*>(bytes), size);
  };
  if (c.encode_exr(file.c_str(), width, height, pixels, channel, sink, &encoded, error, sizeof error) != 0)
    throw std::runtime_error(file.string() + ": cannot encode: " + first_line(error, "encoding failed"));
  write_file_atomically(file, encoded);
}

}  // namespace

namespace {
std::atomic<std::size_t> g_image_files_read{0};
}  // namespace

std::size_t image_files_read() { return g_image_files_read.load(std::memory_order_relaxed); }

Image8 read_image8(const std::filesystem::path& file, int channels) { return read_image8(file, channels, 0, 0); }

Image8 read_image8(const std::filesystem::path& file, int channels, int width, int height) {
  g_image_files_read.fetch_add(1, std::memory_order_relaxed);
  const auto bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, file.string() + ": " + what); };
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw bad("no such file");
  if (!std::filesystem::is_regular_file(file, ec)) throw bad("not a regular file");
  // The header, by the reader of the file's own format (its extension): libpng for a PNG, else the
  // codec module's.
  std::string extension = file.extension().string();
  for (char& ch : extension) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  std::unique_ptr<png::Reader> png_file;
  Opened o;
  ShadowrefImageHeader spec{};
  if (extension == ".png") {
    png_file = std::make_unique<png::Reader>(file);
    if (!png_file->why().empty()) throw bad("cannot open: " + png_file->why());
    spec.width = png_file->width();
    spec.height = png_file->height();
    spec.depth = 1;
    spec.channels = png_file->channels();
    spec.is_uint8 = png_file->bit_depth() == 8;
    std::snprintf(spec.format, sizeof spec.format, "uint%d", png_file->bit_depth());
  } else {
    QuietStderr quiet;
    o = open_image(codec(), file, extension.size() > 1 ? extension.substr(1) : file.string(),
                   "not an image OpenImageIO can read", bad);
    spec = o.header;
  }
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1) throw bad("not a 2D image");
  if (static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) > kMaxPixels)
    throw bad(std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels: larger than 16384 x 16384");
  if (width > 0 && (spec.width != width || spec.height != height))
    throw InputError(InputError::Kind::SizeMismatch, file.string() + ": candidate is " + std::to_string(spec.width) + "x" +
                                                         std::to_string(spec.height) + ", reference is " + std::to_string(width) +
                                                         "x" + std::to_string(height));
  if (channels == 0 && (spec.channels < 1 || spec.channels > 4)) throw bad("has " + std::to_string(spec.channels) + " channels, expected 1 to 4");
  if (channels == 0) channels = spec.channels;  // as the file has them
  if (spec.channels != channels)
    throw bad("has " + std::to_string(spec.channels) + " channel(s), expected " + std::to_string(channels) +
              (channels == 1 ? " (8-bit grey: 255 lit, 0 shadowed, 128 no surface)" : ""));
  if (!spec.is_uint8) throw bad("pixel format " + std::string(spec.format) + ", expected 8-bit unsigned");
  Image8 image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = channels;
  image.pixels.resize(image.pixel_count() * static_cast<std::size_t>(channels));
  if (png_file) {
    if (!png_file->read(image.pixels.data()))
      throw bad("cannot read pixels (truncated or corrupt?): " + png_file->why());
    return image;
  }
  QuietStderr quiet;
  char error[kErrorSize] = "";
  if (codec().read(o.reader.get(), channels, kShadowrefUint8, image.pixels.data(), error, sizeof error) != 0)
    throw bad("cannot read pixels (truncated or corrupt?): " + first_line(error, "decoding failed"));
  return image;
}

Image8 decode_png8(const std::string& bytes, const std::string& name) {
  const auto bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, name + ": " + what); };
  png::Reader r(png::Reader::FromMemory{}, bytes);
  if (!r.why().empty()) throw bad("cannot decode as PNG: " + r.why());
  if (static_cast<std::size_t>(r.width()) * static_cast<std::size_t>(r.height()) > kMaxPixels)
    throw bad(std::to_string(r.width()) + " x " + std::to_string(r.height()) + " pixels: larger than 16384 x 16384");
  if (r.channels() < 1 || r.channels() > 4) throw bad("has " + std::to_string(r.channels()) + " channels, expected 1 to 4");
  if (r.bit_depth() != 8) throw bad("pixel format uint" + std::to_string(r.bit_depth()) + ", expected 8-bit unsigned");
  Image8 image;
  image.width = r.width();
  image.height = r.height();
  image.channels = r.channels();
  image.pixels.resize(image.pixel_count() * static_cast<std::size_t>(image.channels));
  if (!r.read(image.pixels.data())) throw bad("cannot read pixels (truncated or corrupt?): " + r.why());
  return image;
}

std::vector<float> read_exr(const std::filesystem::path& file, int width, int height) {
  const auto bad = [&](const std::string& what) { return InputError(InputError::Kind::BadInput, file.string() + ": " + what); };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw bad("no such file");
  const ShadowrefImageCodec& c = codec();
  QuietStderr quiet;
  const Opened o = open_image(c, file, "exr", "not an OpenEXR file", bad);
  const ShadowrefImageHeader& spec = o.header;
  if (spec.width != width || spec.height != height || spec.depth != 1 || spec.channels != 1)
    throw bad("is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " with " +
              std::to_string(spec.channels) + " channel(s), expected " + std::to_string(width) + "x" +
              std::to_string(height) + " with 1");
  std::vector<float> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  char error[kErrorSize] = "";
  if (c.read(o.reader.get(), 1, kShadowrefFloat, pixels.data(), error, sizeof error) != 0)
    throw bad("cannot read pixels: " + first_line(error, "decoding failed"));
  return pixels;
}

std::string encode_png(const Image8& image) {
  if (image.pixels.size() != image.pixel_count() * static_cast<std::size_t>(image.channels))
    throw std::logic_error("image buffer does not match its size");
  return png::encode(image);
}

void write_png(const Image8& image, const std::filesystem::path& file) {
  if (image.pixels.size() != image.pixel_count() * static_cast<std::size_t>(image.channels))
    throw std::logic_error(file.string() + ": image buffer does not match its size");
  std::string encoded;
  try {
    encoded = png::encode(image);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(file.string() + ": cannot encode: " + e.what());
  }
  write_file_atomically(file, encoded);
}

void write_exr(int width, int height, const float* pixels, const std::filesystem::path& file) {
  write_exr_image(file, width, height, pixels, "Y");
}

}  // namespace shadowref::outputs
