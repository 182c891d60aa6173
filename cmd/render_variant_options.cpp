// render_variant_options.cpp — our renderer's correct variants on the command line, one definition
// for `shadowref render` and `shadowref conform`: an option per row of the renderer's table
// (shadowref/renderer/render_variants.hpp: flag, accepted values, help), bound to that
// RenderOptions field, each declared in candidate.json by the renderer.
#include "render_variant_options.hpp"

#include <CLI/CLI.hpp>

#include <charconv>
#include <string>
#include <type_traits>
#include <vector>

#include "command.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/renderer/render_variants.hpp"

namespace shadowref::cli {
namespace {

// A whole number the row's own rule accepts (its `problem` returns "").
CLI::Validator problem_check(const renderer::RenderVariant& v) {
  return CLI::Validator(
      [problem = v.problem](std::string& text) -> std::string {
        long long n = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
        if (ec != std::errc() || end != text.data() + text.size()) return text + ": not a whole number";
        const std::string p = problem(n);
        return p.empty() ? "" : text + ": " + p;
      },
      std::string(v.accepts), "");
}

void add_variant(CLI::App& cmd, const renderer::RenderVariant& v, renderer::RenderOptions& o) {
  const std::string flag(v.flag), help(v.help);
  std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(o.*member)>;
        T& field = o.*member;
        if constexpr (std::is_same_v<T, bool>) {
          cmd.add_flag(flag, field, help);
        } else if constexpr (std::is_enum_v<T>) {
          std::vector<std::string> names;
          for (T value : renderer::all_values(T{})) names.emplace_back(outputs::to_string(value));
          cmd.add_option_function<std::string>(
                 flag,
                 [&field](const std::string& name) {
                   for (T value : renderer::all_values(T{}))
                     if (name == outputs::to_string(value)) field = value;
                 },
                 help)
              ->check(CLI::IsMember(names))
              ->default_str(outputs::to_string(field));
        } else if (v.problem) {
          cmd.add_option(flag, field, help)->check(problem_check(v))->capture_default_str();
        } else {
          cmd.add_option(flag, field, help)->check(CLI::Range(static_cast<T>(v.min), static_cast<T>(v.max)))->capture_default_str();
        }
      },
      v.field);
}

}  // namespace

void add_render_variant_options(CLI::App& cmd, RenderVariantArgs& args) {
  for (const renderer::RenderVariant& v : renderer::render_variants()) add_variant(cmd, v, args.options);
}

void apply_render_variants(const RenderVariantArgs& a, int shadow_map_size, renderer::RenderOptions& options) {
  if (shadow_map_size + 2 * a.options.guard_band_texels > outputs::kMaxShadowMapSize)
    throw BadInput("--guard-band " + std::to_string(a.options.guard_band_texels) + ": a map of " +
                   std::to_string(shadow_map_size) + " texels with the band on both sides exceeds " +
                   std::to_string(outputs::kMaxShadowMapSize) + " texels");
  renderer::copy_render_variants(a.options, options);
}

}  // namespace shadowref::cli
