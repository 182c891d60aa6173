// image_codec.hpp — the C interface between the contract's image functions (image_io.cpp) and the
// module that holds OpenImageIO (image_codec.cpp, built as libshadowref_image_codec.so).
//
// Why a module: OpenImageIO 2.4 as Debian builds it pulls about 260 shared libraries into a process,
// and binding their symbols costs every process that links it about 0.3 s before main() (measured
// with perf: do_lookup_x in the dynamic loader). Most runs of shadowref that never touch an image
// other than a PNG (a refused argument, a bad scene, `math`, `--help`, a conformance case of a hard
// technique: libpng reads and writes PNGs, png_codec.hpp) then paid for it, and the test command
// runs a thousand such processes. The image functions load this module on their first other image.
//
// The interface is plain C so that no C++ object or exception crosses the module's edge: each call
// returns 0 on success or fills `error` (a NUL-terminated message from OpenImageIO, possibly several
// lines, possibly empty) and returns non-zero.
#pragma once

#include <cstddef>

extern "C" {

// An opened image's header.
struct ShadowrefImageHeader {
  int width, height, depth, channels;
  int is_uint8;     // the pixel format is 8-bit unsigned
  char format[32];  // the pixel format's name ("uint8", "half", ...)
};

enum ShadowrefPixelType { kShadowrefUint8 = 0, kShadowrefFloat = 1 };

struct ShadowrefImageCodec {
  int version;  // kShadowrefImageCodecVersion
  // Opens `file` with the reader of `format` only (a file extension without its dot: "png", "exr")
  // and reads its header. Returns the reader, or null with `error` filled.
  void* (*open)(const char* file, const char* format, ShadowrefImageHeader* header, char* error, std::size_t error_size);
  // Reads `channels` channels of every pixel as `type` into `pixels`, then closes the file (a
  // decoder may report a broken stream only then). The reader stays to be freed.
  int (*read)(void* reader, int channels, int type, void* pixels, char* error, std::size_t error_size);
  void (*free_reader)(void* reader);
  // Encodes a width × height single-channel float image, row 0 at the top, as OpenEXR (zip, the one
  // channel named `channel`, no wall-clock DateTime) in memory, and hands the bytes to
  // sink(context, ...). Returns 0, or non-zero with `error` filled.
  int (*encode_exr)(const char* file, int width, int height, const float* pixels, const char* channel,
                    void (*sink)(void* context, const void* bytes, std::size_t size), void* context, char* error,
                    std::size_t error_size);
};

inline constexpr int kShadowrefImageCodecVersion = 2;

// The module's one exported symbol.
const ShadowrefImageCodec* shadowref_image_codec();
using ShadowrefImageCodecEntry = const ShadowrefImageCodec* (*)();
}
