// shadowref/scene/path_within.hpp — the one test of "this file lies inside that folder", for every
// rule that confines what we read (a scene's meshes, a glTF's buffers, a candidate's files).
#pragma once

#include <algorithm>
#include <filesystem>

namespace shadowref::scene {

// True when `path` is `folder` or lies below it, both already canonical (weakly_canonical:
// symlinks resolved, "." and ".." folded), compared component by component, so /a/bc is not
// within /a/b. Cost: one pass over the components.
inline bool is_within(const std::filesystem::path& folder, const std::filesystem::path& path) {
  return std::mismatch(folder.begin(), folder.end(), path.begin(), path.end()).first == folder.end();
}

// The same for paths not yet canonical; false when either cannot be resolved.
inline bool resolves_within(const std::filesystem::path& folder, const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path f = std::filesystem::weakly_canonical(std::filesystem::absolute(folder, ec), ec);
  if (ec) return false;
  const std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  return !ec && is_within(f, p);
}

}  // namespace shadowref::scene
