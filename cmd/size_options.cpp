// size_options.cpp — the command-line checks of the sizes outputs/limits.hpp defines, shared by
// every subcommand that takes them, so that each accepts and refuses the same values with the same line.
#include <CLI/CLI.hpp>

#include <charconv>
#include <string>

#include "command.hpp"
#include "shadowref/outputs/limits.hpp"

namespace shadowref::cli {

CLI::Validator shadow_map_size_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        long long v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || end != text.data() + text.size()) return text + ": not a whole number";
        const std::string problem = outputs::shadow_map_size_problem(v);
        return problem.empty() ? "" : text + ": " + problem;
      },
      "0 or " + std::to_string(outputs::kMinShadowMapSize) + ".." + std::to_string(outputs::kMaxShadowMapSize), "");
}

}  // namespace shadowref::cli
