// shadowref/scene/identifier.hpp — the safe-identifier rule for every name that becomes a path.
//
// A safe identifier matches [A-Za-z0-9][A-Za-z0-9_.-]{0,63} and holds no "..": 1 to 64 ASCII
// letters, digits, '_', '.' and '-', starting with a letter or a digit. Joined to a folder, it
// names exactly one entry inside that folder, on every platform: no '/' or '\' (no sub-folder), no
// ':' (no drive prefix "C:", no alternate data stream), no leading '.' (not hidden, not "." or
// ".."), no ".." anywhere, not empty, and short enough for any file system.
//
// Scene names and object names in scene files must be safe identifiers (load_scene.hpp); anything
// else that turns a name into a path (technique names, names given on the command line) asks
// the same function, so there is one rule.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace shadowref::scene {

inline constexpr std::size_t kMaxIdentifierLength = 64;

// What is wrong with `name` as a safe identifier, as one line to follow "<where>: " (e.g. "must not
// contain '/'", with the rule in brackets after it), or nullopt when it is one. The first problem
// found, in this order: empty, too long, "..", first character, any other character.
std::optional<std::string> identifier_problem(std::string_view name);

// identifier_problem(name) == nullopt.
bool is_safe_identifier(std::string_view name);

}  // namespace shadowref::scene
