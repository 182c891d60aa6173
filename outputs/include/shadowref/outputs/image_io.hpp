// shadowref/outputs/image_io.hpp — reading and writing the contract's images, row 0 = the top row:
// PNG with libpng, everything else with OpenImageIO. The only PNG / EXR reader and writer of the
// project.
//
// Reading refuses, with a one-line InputError(BadInput) naming the file, everything a comparison
// cannot judge honestly: a missing file, a file libpng or OpenImageIO cannot open or decode (a
// truncated PNG), more than 16384 × 16384 pixels (checked from the header, before any pixel is
// allocated), a channel count other than the one asked for, a pixel format other than 8-bit
// unsigned. Nothing is converted behind the caller's back (an RGB "grey" mask is refused, not
// averaged; a gAMA chunk changes no sample).
//
// Writing: PNG for Image8 (grey or RGB; a fast deflate, no colour-space chunk), OpenEXR (zip, one
// float channel "Y", no wall-clock DateTime so that two runs write identical bytes) for float
// images, each file all or nothing (atomic_file.hpp): FileError naming the file and the system's
// reason when it cannot be written. Callers that need all-or-nothing folders write into a
// StagedFolder (staged_folder.hpp).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "shadowref/outputs/image.hpp"

namespace shadowref::outputs {

// Reads `file` as an 8-bit image with exactly `channels` channels, or with the file's own 1 to 4
// (grey, grey + alpha, RGB, RGBA) when `channels` is 0. Throws InputError(BadInput).
Image8 read_image8(const std::filesystem::path& file, int channels);

// The same, for a file that must be `width` × `height` (a candidate mask beside its reference):
// another size is InputError(SizeMismatch) "<file>: candidate is WxH, reference is WxH", known from
// the header before any pixel is decoded, so a decompression bomb costs no memory.
Image8 read_image8(const std::filesystem::path& file, int channels, int width, int height);

// How many image files read_image8 has been asked to read in this process, all threads: what a test
// of a judgement counts to see that it reads each of a case's files once. Cost: one atomic add per read.
std::size_t image_files_read();

// PNG bytes held in memory (an image embedded in a glTF file) as an 8-bit image with the stream's
// own 1 to 4 channels, by the same reader and checks as read_image8; `name` stands for the file in
// messages. Throws InputError(BadInput) "<name>: <what>".
Image8 decode_png8(const std::string& bytes, const std::string& name);

// Reads a single-channel float image (the reference's visibility.exr) that must be width × height.
// Throws InputError(BadInput) for a missing, unreadable or mis-sized file.
std::vector<float> read_exr(const std::filesystem::path& file, int width, int height);

// Writes `image` as PNG.
void write_png(const Image8& image, const std::filesystem::path& file);
// `image` (1 to 4 channels: grey, grey + alpha, RGB, RGBA) as PNG bytes, for a file that embeds
// them (the pack's glTF mask textures). Throws std::runtime_error with libpng's reason.
std::string encode_png(const Image8& image);

// Writes a width × height single-channel float image (row 0 at the top) as OpenEXR.
void write_exr(int width, int height, const float* pixels, const std::filesystem::path& file);

}  // namespace shadowref::outputs
