// identifier.cpp — the safe-identifier rule (identifier.hpp).
#include "shadowref/scene/identifier.hpp"

#include <cstdio>

namespace shadowref::scene {
namespace {

bool is_alnum(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); }

// A character as a message shows it: 'c' when printable ASCII, else its byte value.
std::string shown(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  char buf[16];
  std::snprintf(buf, sizeof buf, "byte 0x%02X", static_cast<unsigned>(u));
  return buf;
}

constexpr const char* kRule =
    " (a name becomes a file or folder name: 1 to 64 of A-Z a-z 0-9 _ . -, starting with a letter or a digit, no '..')";

}  // namespace

std::optional<std::string> identifier_problem(std::string_view name) {
  const auto problem = [](const std::string& what) { return std::optional<std::string>(what + kRule); };
  if (name.empty()) return problem("must not be empty");
  if (name.size() > kMaxIdentifierLength)
    return problem("must be at most " + std::to_string(kMaxIdentifierLength) + " characters, not " + std::to_string(name.size()));
  if (name.find("..") != std::string_view::npos) return problem("must not contain '..'");
  if (!is_alnum(name.front())) return problem("must start with a letter or a digit, not " + shown(name.front()));
  for (char c : name)
    if (!is_alnum(c) && c != '_' && c != '.' && c != '-') return problem("must not contain " + shown(c));
  return std::nullopt;
}

bool is_safe_identifier(std::string_view name) { return !identifier_problem(name).has_value(); }

}  // namespace shadowref::scene
