// shadowref/outputs/file_names.hpp — the file names of the output contract, per light.
//
// A folder of one producer for one scene holds, for a scene with ONE light, `<stem>.<ext>`
// (mask.png, decided.png, visibility.exr, error.png) and, for N > 1 lights, `<stem>_<i>.<ext>` for
// i = 0 … N−1 in the scene's light order (mask_0.png, mask_1.png, …). These functions are the only
// place that spells the rule.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace shadowref::outputs {

// "<stem>.<ext>" when light_count == 1, else "<stem>_<light>.<ext>". `ext` without the dot.
std::string per_light_name(std::string_view stem, std::string_view ext, std::size_t light, std::size_t light_count);

inline std::string mask_name(std::size_t light, std::size_t light_count) {
  return per_light_name("mask", "png", light, light_count);
}
inline std::string decided_name(std::size_t light, std::size_t light_count) {
  return per_light_name("decided", "png", light, light_count);
}
// The reference's coverage image (one for all lights): 255 where one smooth surface covers the pixel.
inline constexpr const char* kCoveredName = "covered.png";

// The 8-bit lit fraction of a filtered technique (candidates) — the reference's is visibility.exr.
inline std::string visibility_name(std::size_t light, std::size_t light_count) {
  return per_light_name("visibility", "png", light, light_count);
}

// The mask file names present in `dir`: {"mask.png"} or {"mask_0.png", …, "mask_<n-1>.png"} (the
// run of consecutive indices from 0). Throws InputError(BadInput) when `dir` is not a folder, has
// no mask, or has both mask.png and mask_0.png.
std::vector<std::string> find_mask_names(const std::filesystem::path& dir);

}  // namespace shadowref::outputs
