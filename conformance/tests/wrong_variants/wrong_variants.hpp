// wrong_variants.hpp — deliberately wrong shadow techniques, each a classic bug, that the
// conformance suite must catch (its "teeth"): a threshold or a catalogue that lets one of
// them pass is a bug of the suite.
//
// They are separate renderers built from the renderer library's own pieces (frame.hpp: the
// passes, the programs; mathlib: volumes, shadow matrices, projections) and plugged in through
// Renderer::render(scene, Technique). Each is judged as the technique it pretends to be
// (`judged_as`: that technique's catalogue expectations and threshold); a name outside the
// catalogue means "claims to be right everywhere": expected to pass, strictest threshold.
#pragma once

#include <span>

#include "shadowref/renderer/renderer.hpp"

namespace shadowref::wrong {

struct WrongVariant {
  renderer::Technique technique;  // name, what is wrong, the renderer
  const char* judged_as;          // the technique whose expectations and threshold judge it
  const char* caught_by;          // the catalogue scene(s) expected to catch it, for messages
};

std::span<const WrongVariant> wrong_variants();

// The renderers (one file per family).
void render_zfail_without_caps(renderer::Frame& frame);
void render_zfail_half_pixel_offset(renderer::Frame& frame);
void render_planar_transposed(renderer::Frame& frame);
void render_shadowmap_without_bias(renderer::Frame& frame);
void render_shadowmap_compare_reversed(renderer::Frame& frame);

}  // namespace shadowref::wrong
