// file_names.cpp — the per-light naming rule (file_names.hpp).
#include "shadowref/outputs/file_names.hpp"

#include <system_error>

#include "shadowref/outputs/errors.hpp"

namespace shadowref::outputs {

std::string per_light_name(std::string_view stem, std::string_view ext, std::size_t light, std::size_t light_count) {
  std::string name(stem);
  if (light_count != 1) name += "_" + std::to_string(light);
  name += ".";
  name += ext;
  return name;
}

std::vector<std::string> find_mask_names(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) throw InputError(InputError::Kind::BadInput, dir.string() + ": not a folder");
  const bool single = std::filesystem::exists(dir / mask_name(0, 1), ec);
  std::vector<std::string> names;
  for (std::size_t i = 0;; ++i) {
    // Any count above 1 gives the indexed form; the run stops at the first missing index.
    const std::string name = mask_name(i, 2);
    if (!std::filesystem::exists(dir / name, ec)) break;
    names.push_back(name);
  }
  if (single && !names.empty())
    throw InputError(InputError::Kind::BadInput, dir.string() + ": has both mask.png and mask_0.png (one light or several?)");
  if (single) return {mask_name(0, 1)};
  if (names.empty()) throw InputError(InputError::Kind::BadInput, dir.string() + ": no mask.png (or mask_0.png, ...) in it");
  return names;
}

}  // namespace shadowref::outputs
