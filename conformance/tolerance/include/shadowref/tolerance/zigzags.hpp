// shadowref/tolerance/zigzags.hpp — wrong pixels that no texel grid gives together: a shadow edge that
// zigzags faster than any shadow map's staircase can.
//
// Each wrong pixel of a shadow map may be explained alone — a true boundary lies within its texel
// footprint (reference/causes.hpp) — while the pixels together are no map's answer. Where a
// directional light's map (one orthographic view: its turn, texel size per axis and phase the
// candidate's own, unknown) looks up a straight caster edge over one receiver plane, a texel holds
// the caster or not by which side of the edge's line its centre lies on: in the light's plane the
// shadowed texels are a digital half-plane of a rectangular grid. A lookup that is a fixed,
// monotone function of the texels it reads — nearest, a fixed PCF kernel, bilinear PCF, at any
// threshold — then answers monotonically along the edge's normal (for any turn of the grid: its
// axes are perpendicular), and its lit/shadowed boundary is a graph over the edge made of pieces
// along the grid's two axes. So the boundary cannot go down by D1 and back up by D2 (or up, then
// down) within less than 2 sqrt(D1 D2) along the edge: pieces at angle x to the edge take
// D1 cot x + D2 tan x. Three candidate pixels on the plane — lit, shadowed, lit (or the reverse) in
// their order along the edge, the middle one that far past both along the normal, the outer two
// closer together along the edge than that — are no such map's answer, and their wrong pixels
// count as unexplained (docs/tolerance-model.md, "Zigzags"). A perspective warp of the light's
// plane (LiSPSM, trapezoidal maps) skews its cells, and a skewed grid's staircase may fold back
// along the normal: such a map is no `own` view of this kind (nor of the cause model's), and an
// engine that draws one declares its matrices, where this check does not apply.
//
// The conditions are checked, not assumed. In a window the check looks at, every surface a texel
// within the reach of a window pixel's lookup may store (grid uncertainty plus the filter's radius
// in texels, √2 for an unknown turn, plus a declared normal offset; the first face, the face
// behind culled front faces, what lies behind a culled open mesh: CauseModel::stored_along) is
// sampled every 1/4 texel and must shadow every window pixel whatever bias a correct map adds (up
// to the bias a correct map needs) or light every one (the receiver's own plane, a farther surface,
// nothing); a sample that may do either is allowed only between the two kinds (a ray grazing a
// silhouette). A triple counts only where the samples within reach of the box it spans along the
// edge and its normal are separated by a straight line, and it must hold over the whole range of
// that line's normal. A contact, a corner, a second caster or a curve within reach leaves the
// triple alone.
//
// Applies to a directional light's one map (not cascaded: a split changes the grid) with a fixed
// kernel (sampling "grid") and the candidate's own or the pack's views, the shadowmap and PCF
// families. Looked at only where the candidate leaves more wrong pixels in one 9 × 9 window than
// the local-glitch bound allows unexplained and crosses a row or a column of the 21 × 21 window
// around it more often than the reference does (a moved edge keeps its crossings; a zigzag adds
// them). Cost: per window (at most kMaxZigzagWindows per mask), one primary ray per window pixel
// and up to 128 × 128 light-plane samples of a few rays each; most of its time is the separating
// line's search, an angle scan over the samples' hulls, per wrong pixel (bench/judge_bench.cpp:
// 8 ms a window on grazing_light's tile).
#pragma once

#include <cstddef>
#include <vector>

#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {
class CauseModel;
}

namespace shadowref::tolerance {

// Windows looked at per mask, the densest first: bounds the cost of a mask wrong all over (which
// FAILs on its own count anyway).
inline constexpr std::size_t kMaxZigzagWindows = 24;

// A candidate's answer at a point of the light's plane, in the frame of a straight caster edge:
// `e` along the edge, `s` along its normal into the shadow (any one unit of length).
struct EdgePoint {
  double e = 0, s = 0;
  bool shadowed = false;
};

// The certificate: whether no map on a rectangular texel grid (any turn, texel size per axis and
// phase) gives the three answers together. `first` and `last` share one answer and `middle` has
// the other on the far side of both from where it belongs — a lit middle deeper into the shadow
// than two shadowed points, a shadowed middle nearer the light than two lit ones — in that order
// along the edge, `first` and `last` closer along it than 2 sqrt(D1 D2), D1 and D2 the middle's
// distances past them along the normal: the boundary would go down and back up (or up and back
// down) faster than any staircase of such a grid can.
bool no_grid_gives(const EdgePoint& first, const EdgePoint& middle, const EdgePoint& last);

// Whether light `light`'s answers are checked: a directional light, technique `technique` of the
// shadowmap or PCF family and not cascaded, a fixed kernel.
bool zigzags_apply(const scene::PreparedScene& scene, std::size_t light, const outputs::TechniqueName* technique,
                   const outputs::CandidateDeclaration& light_declaration);

struct ZigzagFinding {
  std::vector<std::size_t> impossible;  // wrong pixels (row-major indices) in a certified zigzag
  std::size_t windows = 0;              // windows looked at
  std::size_t judged = 0;               // of those, windows whose conditions held
};

// The check of light `light`'s candidate mask against its reference mask (one size, rows from the
// top), given the wrong pixels (compare.hpp's ImpossiblePixels), under the light's declaration.
ZigzagFinding find_zigzags(const reference::CauseModel& model, const scene::PreparedScene& scene, std::size_t light,
                           const outputs::CandidateDeclaration& light_declaration, const outputs::Image8& reference,
                           const outputs::Image8& candidate, const std::vector<std::size_t>& wrong);

}  // namespace shadowref::tolerance
