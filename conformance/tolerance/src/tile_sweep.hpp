// tile_sweep.hpp — every place of an 8 × 8 tile swap on one light's mask, judged at the cost of two
// comparisons: the resolving power's check that no tile passes where its probes all FAIL.
//
// A tile swap at (x0, y0) gives each pixel of [x0, x0 + 16) × [y0, y0 + 8) whose answer differs
// from its partner's 8 px across the partner's answer. Whether a wrong pixel is explained depends
// only on the light, the pixel, the candidate's answer there and the declaration
// (reference::CauseModel::explain; compare_mask's classes), never on the pixels around it. So one
// comparison of the mask with every such pixel flipped (lit and shadowed exchanged) and one with
// every such pixel's surface taken away or given (a coverage change) say, for every pixel and every
// tile, whether it would be unexplained; the tile's own metrics follow from summed-area tables of
// those flags: its unexplained count, cores and densest 9 × 9 window exactly as compare_mask counts
// them for that tile alone (a tile's wrong pixels lie in its box), and compare::decide gives the
// verdict. Without the zigzag check (it adds unexplained pixels, never removes one) and the
// displaced-shadow search (it only adds a FAIL reason): a tile that FAILs here FAILs, and one that
// does not is judged alone, in full, by the caller.
//
// Cost: two mask comparisons (each asking the cause model about every pixel within 8 px across of
// a boundary, once per answer; the judge's memo keeps the answers), then O(1) per place and a
// 9 × 9 count per pixel of the few tiles left.
#pragma once

#include <cstddef>
#include <vector>

#include "shadowref/compare/compare.hpp"
#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/outputs/image.hpp"

namespace shadowref::tolerance {

// The places of light `light`'s `mask` (its reference's `decided`) where a tile swap changes more
// decided pixels than the local-glitch bound in one 9 × 9 window (densest_change) and does not FAIL
// `threshold` without the zigzag check and the displaced-shadow search (`options`' are ignored), in
// row-major order.
std::vector<TilePlace> tiles_not_failing(const outputs::Image8& mask, const outputs::Image8& decided, std::size_t light,
                                         const compare::Threshold& threshold, const compare::CompareOptions& options);

}  // namespace shadowref::tolerance
