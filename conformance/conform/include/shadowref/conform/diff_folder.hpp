// shadowref/conform/diff_folder.hpp — what `shadowref diff --out DIR` writes: DIR/diff.html (the
// page, report/diff_html.hpp) and DIR/diff-images/, per changed case and light, copies of both runs'
// candidate mask and error image and the picture of where the masks differ (mask_difference.hpp),
// written by the one PNG writer (outputs/image_io.hpp).
//
// Nothing is written outside DIR, and only those two names in it: diff-images/ is a staged folder
// (all or nothing, replacing an earlier diff's) and diff.html is written atomically after it, so a
// diff.html always shows images of its own diff. The images' folder names come from the case's
// index, scene and technique with every character but letters, digits, '-', '_' and '.' replaced,
// so no name a report.json holds can lead out of DIR.
#pragma once

#include <filesystem>

#include "shadowref/conform/run_diff.hpp"

namespace shadowref::conform {

// Writes the page and its images for `diff` under `out`. Returns the page's path. Throws
// outputs::FileError (an unwritable DIR, an image that cannot be read), outputs::InputError (a mask
// that does not decode).
std::filesystem::path write_diff_folder(const RunDiff& diff, const std::filesystem::path& out);

}  // namespace shadowref::conform
