// png_codec.cpp — PNG through libpng (png_codec.hpp says why here and not in the codec module).
// Follows libpng's manual (libpng-manual.txt, "Reading PNG files" and the simplified write API).
#include "png_codec.hpp"

#include <png.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace shadowref::outputs::png {

std::string encode(const Image8& image) {
  if (image.channels < 1 || image.channels > 4)
    throw std::logic_error("a PNG is written with 1 to 4 channels, not " + std::to_string(image.channels));
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  constexpr png_uint_32 kFormats[] = {PNG_FORMAT_GRAY, PNG_FORMAT_GA, PNG_FORMAT_RGB, PNG_FORMAT_RGBA};
  png.format = kFormats[image.channels - 1];
  // Fast: a conformance run writes several images per case, and at 1024² a full deflate was a
  // quarter of the run's CPU time (bench/README.md, "conform at 1024²"); masks are large flat
  // regions, which the fast level still compresses well. No colour-space chunk: the masks are
  // data, and shaded.png's sRGB is the contract's (image.hpp).
  png.flags = PNG_IMAGE_FLAG_FAST | PNG_IMAGE_FLAG_COLORSPACE_NOT_sRGB;
  // The bound libpng states for the whole stream: one encoding, never two (a null buffer would
  // only measure).
  std::string encoded(PNG_IMAGE_PNG_SIZE_MAX(png), '\0');
  png_alloc_size_t size = encoded.size();
  if (!png_image_write_to_memory(&png, encoded.data(), &size, 0, image.pixels.data(), 0, nullptr)) {
    const std::string why = png.message;
    png_image_free(&png);
    throw std::runtime_error(why.empty() ? "libpng failed" : why);
  }
  encoded.resize(size);
  return encoded;
}

// libpng reports an error by calling on_error, which must not return: it longjmps to the setjmp of
// the function that called libpng (png_jmpbuf). So the two functions below that call libpng hold
// no C++ object with a destructor, and everything they touch is plain data in State.
struct Reader::State {
  png_structp png = nullptr;
  png_infop info = nullptr;
  std::FILE* file = nullptr;
  char why[512] = "";
};

namespace {

void on_error(png_structp png, png_const_charp message) {
  auto* why = static_cast<char*>(png_get_error_ptr(png));
  std::strncpy(why, message ? message : "libpng error", 511);
  why[511] = '\0';
  png_longjmp(png, 1);
}

// Warnings (an sRGB profile libpng knows to be wrong, a damaged ancillary chunk it skips) change
// nothing it decodes; the command line prints one line per failure, and this is none.
void on_warning(png_structp, png_const_charp) {}

bool read_header(Reader::State& s) {
  if (setjmp(png_jmpbuf(s.png))) return false;
  png_init_io(s.png, s.file);
  png_read_info(s.png, s.info);
  png_set_expand(s.png);  // what OpenImageIO's reader does (png_codec.hpp)
  png_set_interlace_handling(s.png);
  png_read_update_info(s.png, s.info);
  return true;
}

bool read_rows(Reader::State& s, png_bytepp rows) {
  if (setjmp(png_jmpbuf(s.png))) return false;
  png_read_image(s.png, rows);
  png_read_end(s.png, nullptr);  // the CRC of the last IDAT and the chunks after it
  return true;
}

}  // namespace

Reader::Reader(const std::filesystem::path& file) : state_(new State) {
  state_->file = std::fopen(file.c_str(), "rb");
  open();
}

// fmemopen in "r" mode reads the buffer and never writes it.
Reader::Reader(FromMemory, const std::string& bytes) : state_(new State) {
  state_->file = bytes.empty() ? nullptr : fmemopen(const_cast<char*>(bytes.data()), bytes.size(), "rb");
  if (bytes.empty()) errno = EINVAL;
  open();
}

void Reader::open() {
  if (!state_->file) {
    why_ = std::strerror(errno);
    return;
  }
  state_->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, state_->why, on_error, on_warning);
  if (state_->png) state_->info = png_create_info_struct(state_->png);
  if (!state_->png || !state_->info) {
    why_ = "libpng cannot allocate its structures";
    return;
  }
  if (!read_header(*state_)) {
    why_ = state_->why[0] ? state_->why : "libpng error";
    return;
  }
  width_ = static_cast<int>(png_get_image_width(state_->png, state_->info));
  height_ = static_cast<int>(png_get_image_height(state_->png, state_->info));
  channels_ = png_get_channels(state_->png, state_->info);
  bit_depth_ = png_get_bit_depth(state_->png, state_->info);
}

Reader::~Reader() {
  if (state_->png) png_destroy_read_struct(&state_->png, state_->info ? &state_->info : nullptr, nullptr);
  if (state_->file) std::fclose(state_->file);
  delete state_;
}

bool Reader::read(std::uint8_t* pixels) {
  if (!why_.empty()) return false;
  const std::size_t row_bytes = png_get_rowbytes(state_->png, state_->info);
  std::vector<png_bytep> rows(static_cast<std::size_t>(height_));
  for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = pixels + y * row_bytes;
  if (!read_rows(*state_, rows.data())) {
    why_ = state_->why[0] ? state_->why : "libpng error";
    return false;
  }
  return true;
}

}  // namespace shadowref::outputs::png
