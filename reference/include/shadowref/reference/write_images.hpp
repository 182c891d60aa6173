// shadowref/reference/write_images.hpp — the reference's output folder (DESIGN.md "Outputs").
//
// Writes, with OpenImageIO, row 0 = the top row:
//   one light:  mask.png, visibility.exr, decided.png, shaded.png
//   N lights:   mask_<i>.png, visibility_<i>.exr, decided_<i>.png for each light i, plus the
//               aggregates visibility.exr (mean over lights) and decided.png (AND), and shaded.png.
// mask and decided are 8-bit grey, shaded 8-bit RGB, visibility 32-bit float, one channel "Y".
// Every file is first written under a temporary name in `dir` and renamed only after all files
// are complete, so a crash never leaves a half-written image under a final name.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shadowref/reference/render.hpp"

namespace shadowref::reference {

// Creates `dir` if needed and writes the images; returns the file names written (sorted).
// Throws std::runtime_error naming the file when OpenImageIO or the file system fails.
std::vector<std::string> write_images(const Images& images, const std::filesystem::path& dir);

}  // namespace shadowref::reference
