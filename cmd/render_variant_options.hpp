// render_variant_options.hpp — our renderer's correct variants on the command line, the same in
// `render` and `conform` (render_variant_options.cpp): an option per row of
// renderer::render_variants(), bound to that field of `options` (whose other fields are unused).
// Apart from command.hpp so that the commands without a renderer (the math ones, the fuzzers)
// need not see RenderOptions.
#pragma once

#include <CLI/CLI.hpp>

#include "shadowref/renderer/renderer.hpp"

namespace shadowref::cli {

struct RenderVariantArgs {
  renderer::RenderOptions options;
};
void add_render_variant_options(CLI::App& cmd, RenderVariantArgs& args);
// Sets `options`' variant fields from `args` (the other fields are kept); BadInput when the guard
// band would make a map of `shadow_map_size` texels larger than the limit.
void apply_render_variants(const RenderVariantArgs& args, int shadow_map_size, renderer::RenderOptions& options);

}  // namespace shadowref::cli
