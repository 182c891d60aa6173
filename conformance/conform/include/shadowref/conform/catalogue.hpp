// shadowref/conform/catalogue.hpp — which scene files a conformance run takes.
//
// The catalogue is a folder of scene files (conformance/scenes/*.json; a folder may also hold glTF
// scenes, *.gltf and *.glb with a camera and a light, as a pack's scenes/ does for one exported from
// a glTF: scene/gltf_scene.hpp's holds_camera_and_light; a glTF mesh file beside a JSON scene is
// none). A selection is a
// comma-separated list of patterns: an existing file path is taken as it is; anything else is a
// shell glob (fnmatch: *, ?, [..]) matched against the catalogue's file names, with or without
// their extension ("ground_*", "*light*", "my_level.gltf"). Without patterns, every scene except those tagged "large" (the default
// run stays fast on two cores; name a large scene to include it).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace shadowref::conform {

// The folder the data lives in, which keeps the source tree's layout (conformance/scenes with its
// meshes, goldens/images, pack/README.template.md). Installed, it is found relative to the running binary (/proc/self/exe):
// <prefix>/bin/shadowref reads <prefix>/share/shadowref. A binary inside the build tree (the build's
// `shadowref` and every test) reads the source tree, a compile-time path; so does a binary that
// cannot see /proc/self/exe. An installed binary whose data is missing still answers the installed
// folder, so that the error names it and no source path is ever used outside the build tree.
std::filesystem::path data_dir();

// The default catalogue: data_dir()/conformance/scenes.
std::filesystem::path default_catalogue();

// The reference masks `shadowref goldens` checks: data_dir()/goldens/images.
std::filesystem::path default_golden_images();

// The scene files selected by `patterns` (may be empty: the default selection), sorted by name,
// each once. Throws std::invalid_argument when a pattern matches nothing or the catalogue is not a
// folder (a typo must not silently shrink a run). Loading them is the caller's business; the
// "large" tag is read from the JSON here.
std::vector<std::filesystem::path> select_scenes(const std::filesystem::path& catalogue,
                                                 const std::vector<std::string>& patterns);

// What every command's --scenes takes (select_scenes over split_list), said once for their --help.
inline constexpr const char* kScenesHelp =
    "comma-separated globs over the catalogue's scene names, or scene files: JSON, or your own glTF 2.0 scene "
    "(.gltf, .glb: a camera, KHR_lights_punctual lights; docs/scene-format.md) (e.g. ground_sphere,soft_*,my_level.gltf); "
    "default: every scene not tagged 'large'";

// Splits "a,b, c" into {"a", "b", "c"} (empty items dropped).
std::vector<std::string> split_list(const std::string& text);

}  // namespace shadowref::conform
