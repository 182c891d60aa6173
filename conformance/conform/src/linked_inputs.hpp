// linked_inputs.hpp — which of the files a candidate folder gave us were read through a symbolic
// link that leads out of that folder.
//
// Reading through links is allowed (CI systems lay candidate folders out as symlink forests), but
// a verdict is about the files that were judged, so report.json names every input whose real
// location is outside the folder it was handed in, with where it resolves to.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace shadowref::conform {

struct LinkedInput {
  std::string file;         // as read: inside `root`
  std::string resolves_to;  // its canonical location, outside `root`
};

// For each of `files` (paths below `root`) that exists: a LinkedInput when its canonical path does
// not lie under `root`'s canonical path. Costs one canonicalisation per file.
std::vector<LinkedInput> inputs_outside(const std::filesystem::path& root, const std::vector<std::filesystem::path>& files);

}  // namespace shadowref::conform
