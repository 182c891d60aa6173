// shadowref/conform/catalogue.hpp — which scene files a conformance run takes.
//
// The catalogue is a folder of scene files (conformance/scenes/*.json). A selection is a
// comma-separated list of patterns: an existing file path is taken as it is; anything else is a
// shell glob (fnmatch: *, ?, [..]) matched against the catalogue's file names without ".json"
// ("ground_*", "*light*"). Without patterns, every scene except those tagged "large" (the default
// run stays fast on two cores; name a large scene to include it).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace shadowref::conform {

// The default catalogue: <source tree>/conformance/scenes (a compile-time path).
std::filesystem::path default_catalogue();

// The scene files selected by `patterns` (may be empty: the default selection), sorted by name,
// each once. Throws std::invalid_argument when a pattern matches nothing or the catalogue is not a
// folder (a typo must not silently shrink a run). Loading them is the caller's business; the
// "large" tag is read from the JSON here.
std::vector<std::filesystem::path> select_scenes(const std::filesystem::path& catalogue,
                                                 const std::vector<std::string>& patterns);

// Splits "a,b, c" into {"a", "b", "c"} (empty items dropped).
std::vector<std::string> split_list(const std::string& text);

}  // namespace shadowref::conform
