// shadowref/tolerance/resolving_power.hpp — what a verdict could have seen: the known blatant errors
// applied to the reference's own masks, each judged under the candidate's declaration by the same
// comparison as the candidate.
//
// A PASS says the candidate's errors were within what its declaration explains; it does not say how
// large an error that declaration would have let through. A 512-texel map of the candidate's own
// views, or a camera at the light, can explain a one-pixel shift of every shadow. So every judged
// case is asked, with the same threshold, causes and declaration, about probes of the reference's own
// masks (the probes follow the declaration grid's blatant mutants, conformance/tests/):
//   shifted 1 and 2 px in the eight directions (shadows move, surfaces stay),
//   the shadows grown and shrunk by 1 px,
//   an 8 × 8 tile swapped with the one to its right at the three places of the boundary where
//   that changes most pixels (tile_places below), and then at every other place (the tile sweep,
//   tolerance/src/tile_sweep.hpp), since a declaration may explain a tile at one place of a boundary
//   and not at another (a 512-texel map explains more where its texels are long on the ground, and
//   a tile across a gentle stretch of boundary changes few pixels in any window).
// A probe that changes decided pixels and does not FAIL is one the case is blind to; where the three
// tile probes FAIL, the first tile the sweep finds passing is listed as a probe of its own ("an 8x8
// tile swapped at (x, y)"), so that "resolves … 8x8 tiles" holds at every place. Soft techniques are probed on their masks
// alone (a probe of the lit fraction would need a fraction to move; the mask's is what it shows).
//
// A probe that changes no decided pixel (a shift along a straight boundary) proves nothing: it counts
// for neither side. Nor does a tile that changes no more decided pixels than the local-glitch bound
// (compare/thresholds.hpp, kLocalGlitch: 18): a glitch that small is within the runs correct renders
// leave along a boundary, so no verdict promises to see it (a tile placed where the boundary barely
// changes over 8 px, or where no cast shadow is in view). The bound counts one 9 × 9 window, so a
// tile counts by its densest window (densest_change): 27 pixels spread over a tile's 16 × 8 may hold
// no more than 18 in any window, and pass unexplained.
//
// Cost: 21 mask comparisons per light (no error image painted), each asking the cause model about
// the probe's wrong pixels (a few thousand at 256²), first without the displaced-shadow search; then,
// where the tile probes FAIL, the sweep's two comparisons (every pixel within 8 px across of a
// boundary) and a full comparison per place it leaves, until one passes. The judge caches the answer
// per reference, declaration and threshold, and the model's answers per pixel and declaration, so
// that the probes ask about each boundary pixel once (docs/tolerance-model.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "shadowref/compare/compare.hpp"
#include "shadowref/outputs/image.hpp"

namespace shadowref::tolerance {

// The kinds of blatant error probed, each a group of probes.
enum class ProbeKind { Shift1, Shift2, Grown1, Shrunk1, Tile8 };
const char* to_string(ProbeKind k);  // "1-px shifts", "2-px shifts", "1-px growth", "1-px shrinkage", "8x8 tiles"

struct Probe {
  ProbeKind kind;
  std::string name;  // "shifted 1 px right and down", "grown 1 px", ...
  compare::Verdict verdict = compare::Verdict::Pass;
  std::size_t wrong = 0, unexplained = 0;  // on the decided pixels, summed over the lights
  std::size_t densest_changed = 0;         // a tile's: densest_change, the most over the lights
  // Whether the probe counts (above): it changes a decided pixel; a tile, more than kLocalGlitch's
  // bound in one 9 x 9 window.
  bool shows_something() const;
};

struct ResolvingPower {
  std::vector<Probe> probes;
  // A probe that shows nothing (Probe::shows_something) counts for neither side. Per kind:
  // `resolved`, every probe that shows something FAILs; `blind`, one of them does not; `unseen`,
  // none shows anything.
  std::vector<ProbeKind> resolved, blind, unseen;
  // "resolves 1-px shifts, 2-px shifts, 1-px growth, 1-px shrinkage and 8x8 tiles at every place
  // along the boundary", or "blind to
  // 1-px shifts (3 of 7 pass) under this declaration; resolves ...; no decided pixel changes under
  // 2-px shifts; no 8x8 tile changes more than 18 decided pixels in one 9x9 window".
  std::string summary() const;
  bool blind_to(ProbeKind k) const;
  bool sees_nothing_of(ProbeKind k) const;  // k is in `unseen`
};

// `mask` with every surface pixel given the answer of the surface pixel (dx, dy) behind it: its
// shadows moved by (dx, dy), silhouettes kept (the shift probes, and the declaration grid's shift
// mutants). Cost: one pass over the mask.
outputs::Image8 shifted(const outputs::Image8& mask, int dx, int dy);

// A place of an 8 × 8 tile swap: the tile's top-left pixel; the tile swaps with the one 8 px to its
// right.
struct TilePlace {
  int x = 0, y = 0;
};
inline constexpr std::size_t kBusiestTilePlaces = 3;  // the first places, by pixels changed: the tile probes'

// The first `count` places of a tile swap on `mask`'s 4-px lattice, each at least 16 px from the
// earlier ones on an axis: the kBusiestTilePlaces where a swap changes most pixels (the first best
// kept on ties; the busiest places of the boundaries, wherever they lie), then, among the windows
// whose swap changes more pixels than the local-glitch bound, the one farthest (Euclidean) from every
// place taken, the busier on ties (farthest-point sampling: spread along every boundary in view).
// Fewer when no window is left; none when the image is narrower than 16 px or shorter than 8. A
// prefix of a longer list: the places after kBusiestTilePlaces are the ones farthest from every
// probe (the held-out tiles of conformance/tests/). Cost: one pass over the lattice, then one per place.
std::vector<TilePlace> tile_places(const outputs::Image8& mask, std::size_t count);

// The most decided pixels that differ between `before` and `after` in one 9 × 9 window centred on
// one of them (the local-glitch bound's window, compare::densest_window: a tile that changes more
// unexplained pixels than the bound there FAILs). Cost: one pass over the masks, then one 9 × 9
// count per changed pixel.
std::size_t densest_change(const outputs::Image8& before, const outputs::Image8& after, const outputs::Image8& decided);

// `mask` with the 8 × 8 tile at `place` swapped with the one 8 px to its right (a tiled GPU's or a
// cache's local glitch); the place must lie within the image (tile_places' do).
outputs::Image8 swapped_tile_at(const outputs::Image8& mask, TilePlace place);

// `mask` with the tile at the `rank`-th of its tile_places (0: first) swapped; the mask unchanged
// when it has no such place. The declaration grid's tile mutants are these, on our render's masks.
outputs::Image8 swapped_tile(const outputs::Image8& mask, int rank);

// The probes of the reference's masks (one per light, `masks[i]` with its decided pixels
// `decided[i]`, as compare::read_folder_images reads them) judged by `threshold` with `options` (its
// lit-fraction bounds ignored).
ResolvingPower resolving_power(const std::vector<outputs::Image8>& masks, const std::vector<outputs::Image8>& decided,
                               const compare::Threshold& threshold, const compare::CompareOptions& options);

// A case's resolving power as report.json and `shadowref compare --json` give it: {"summary",
// "blind_to": [kinds], "unseen": [kinds], "probes": [{"probe", "verdict", "wrong", "unexplained"}]}.
nlohmann::json resolving_power_json(const ResolvingPower& r);

}  // namespace shadowref::tolerance
