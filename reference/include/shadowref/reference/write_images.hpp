// shadowref/reference/write_images.hpp — the reference's output folder (docs/output-contract.md).
//
// Writes, with OpenImageIO, row 0 = the top row:
//   one light:  mask.png, visibility.exr, decided.png, shaded.png
//   N lights:   mask_<i>.png, visibility_<i>.exr, decided_<i>.png for each light i, plus the
//               aggregates visibility.exr (mean over lights) and decided.png (AND), and shaded.png.
// mask and decided are 8-bit grey, shaded 8-bit RGB, visibility 32-bit float, one channel "Y".
// The files go straight into `dir` (created when missing): callers that need all-or-nothing write
// into an outputs::StagedFolder, so that a crash never leaves a half-written folder under its name.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shadowref/reference/render.hpp"

namespace shadowref::reference {

// Writes the images into the folder `dir`; returns the file names written (sorted).
// Throws std::runtime_error naming the file when OpenImageIO or the file system fails.
std::vector<std::string> write_images(const Images& images, const std::filesystem::path& dir);

}  // namespace shadowref::reference
