// shadowref/compare/displacement.hpp — displaced shadows: a mask whose unexplained errors come
// right when its shadows are moved by a pixel or two, or grown or shrunk by one or two.
//
// Why it is a cause of its own (docs/tolerance-model.md, "Displaced shadows"). Every honest error
// the cause model knows (a texel's footprint, a bias, a filter) lies where a map's texels or its
// bias put it, and none follows the screen's pixel grid: a coarse map's staircases fall on both
// sides of a true boundary, a bias moves boundaries in the light's direction, not the camera's. A
// mask that is the reference moved in screen space — a half-pixel offset, a viewport off by one, a
// shadow dilated by a post-process — matches it again when moved back, and under a generous
// declaration (a small map, a wide filter) most of its wrong pixels may still fall within an
// honest footprint. So the pixels that no cause explains are asked one more question: do they come
// right when the whole mask is moved? Where they do, and the mask moved back also agrees better
// with the reference as a whole (fewer shadow errors on the judged pixels: the move is the mask's
// own, not a few pixels' accident that breaks the rest), they are counted as displaced, and
// thresholds.hpp (kDisplaced) bounds them. The condition on the whole mask does not depend on the
// declaration, and a smaller declaration leaves more pixels unexplained, so declaring less never
// lowers the count.
//
// The moves: translations by (dx, dy), |dx|, |dy| <= 2, not both 0, and the shadows grown or shrunk
// by 1 or 2 px (a square neighbourhood). A moved mask keeps its surfaces: a pixel takes a moved
// answer only where the pixel it comes from is a surface too (coverage is judged apart).
// Cost: one pass over the candidate (its boundaries), then, per move (28), the unexplained pixels
// and the band within 3 px of a boundary alone; only for a mask with unexplained pixels. On a 2048²
// pair whose disc is shifted 2 px (bench/compare_bench.cpp, one core, quiet): 18 ms on top of
// compare_mask's 9.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "shadowref/outputs/image.hpp"

namespace shadowref::compare {

// A screen-space move of a mask's shadows. (dx, dy): the mask's answers come from (x - dx, y - dy),
// i.e. its shadows lie (dx, dy) px away from the reference's (x right, y down); grow > 0: its
// shadows grown by `grow` px, < 0: shrunk.
struct ShadowMove {
  int dx = 0, dy = 0;
  int grow = 0;
};

// "shadows moved 1 px right", "shadows grown by 2 px", ...
std::string describe(const ShadowMove& move);

struct Displacement {
  ShadowMove move;                    // the move (undone) that makes most unexplained pixels right
  std::size_t fixed_unexplained = 0;  // unexplained shadow errors right once the move is undone
  std::size_t wrong_before = 0;       // shadow errors (lit against shadowed) on judged pixels
  std::size_t wrong_after = 0;        // the same once the move is undone
};

// The move of the candidate's shadows that, undone, makes the most `unexplained` pixels (indices of
// unexplained lit/shadowed errors) right among those that lower its shadow errors on the judged
// pixels (decided with a surface in the reference; with `invariant`, also undecided pixels the
// reference sees lit, where a false shadow is judged): `shadow_errors` of them as it is (the
// comparison's false shadows and false light). fixed_unexplained is 0 where no move does. The
// candidate holds the three mask values only (the comparison refuses others first); the images are
// one size.
Displacement find_displacement(const outputs::Image8& reference, const outputs::Image8& decided,
                               const outputs::Image8& candidate, bool invariant,
                               const std::vector<std::size_t>& unexplained, std::size_t shadow_errors);

}  // namespace shadowref::compare
