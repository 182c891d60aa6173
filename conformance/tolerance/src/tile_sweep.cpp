// tile_sweep.cpp — tile_sweep.hpp: two comparisons of answer-changed masks, then every tile place's
// metrics read from summed-area tables of which pixels would be unexplained.
#include "tile_sweep.hpp"

#include <algorithm>
#include <cstdint>

#include "shadowref/compare/thresholds.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/interruption.hpp"

namespace shadowref::tolerance {
namespace {

using outputs::Image8;
using outputs::kMaskLit;
using outputs::kMaskNoSurface;
using outputs::kMaskShadowed;

constexpr int kTile = 8;  // a tile's side, and the distance to its partner

// A summed-area table of a w × h image of 0 / 1 flags: the flags of any box in O(1).
class Table {
 public:
  Table(int w, int h) : w_(w), h_(h), s_(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1)) {}
  // Set after every flag is given (add) and before any sum.
  void add(int x, int y) { ++s_[index(x + 1, y + 1)]; }
  void integrate() {
    for (int y = 1; y <= h_; ++y)
      for (int x = 1; x <= w_; ++x) s_[index(x, y)] += s_[index(x - 1, y)] + s_[index(x, y - 1)] - s_[index(x - 1, y - 1)];
  }
  // The flags in [x0, x1) × [y0, y1), clipped to the image.
  int sum(int x0, int y0, int x1, int y1) const {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, w_), y1 = std::min(y1, h_);
    if (x0 >= x1 || y0 >= y1) return 0;
    return s_[index(x1, y1)] - s_[index(x0, y1)] - s_[index(x1, y0)] + s_[index(x0, y0)];
  }

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w_ + 1) + static_cast<std::size_t>(x); }
  int w_, h_;
  std::vector<std::int32_t> s_;
};

// Per pixel, flags of the two halves of a tile: `left` where the pixel changes as the left half's
// (its partner 8 px to the right), `right` as the right half's (its partner 8 px to the left).
struct HalfFlags {
  Table left, right;
  // The flags within [x0, x1) × [y0, y1) of the tile at (tx, ty): the left half's over its left
  // box, the right half's over its right box (a tile's changes lie in its own box).
  int in_tile(int tx, int ty, int x0, int y0, int x1, int y1) const {
    y0 = std::max(y0, ty), y1 = std::min(y1, ty + kTile);
    return left.sum(std::max(x0, tx), y0, std::min(x1, tx + kTile), y1) +
           right.sum(std::max(x0, tx + kTile), y0, std::min(x1, tx + 2 * kTile), y1);
  }
};

std::uint8_t at(const Image8& m, int x, int y) { return m.pixels[static_cast<std::size_t>(y * m.width + x)]; }

}  // namespace

std::vector<TilePlace> tiles_not_failing(const Image8& mask, const Image8& decided, std::size_t light,
                                         const compare::Threshold& threshold, const compare::CompareOptions& options) {
  const int w = mask.width, h = mask.height;
  if (w < 2 * kTile || h < kTile) return {};
  // `pairs(x, y)`: the swap of a tile whose left half holds (x, y) changes it and (x + 8, y).
  const auto pairs = [&](int x, int y) { return x + kTile < w && at(mask, x, y) != at(mask, x + kTile, y); };
  const auto changes = [&](int x, int y) { return pairs(x, y) || (x >= kTile && pairs(x - kTile, y)); };
  // Every pixel a swap can change, given the other surface answer (flipped) or its coverage changed
  // (covered): a changed pixel's new answer is one of the two, by whether a surface is on both sides.
  Image8 flipped = mask, covered = mask;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!changes(x, y)) continue;
      const std::size_t i = static_cast<std::size_t>(y * w + x);
      const std::uint8_t v = mask.pixels[i];
      if (v != kMaskNoSurface) flipped.pixels[i] = v == kMaskLit ? kMaskShadowed : kMaskLit;
      covered.pixels[i] = v == kMaskNoSurface ? kMaskLit : kMaskNoSurface;
    }
  compare::CompareOptions o = options;
  o.impossible = nullptr;          // adds unexplained pixels only: the caller's full judgement has it
  o.displacement_up_to = -1;       // adds a FAIL reason only: likewise
  o.error_image = false;
  o.list_unexplained = true;
  const compare::MaskComparison flip = compare::compare_mask(mask, decided, flipped, "tile sweep", light, o);
  outputs::throw_if_interrupted();
  const compare::MaskComparison cover = compare::compare_mask(mask, decided, covered, "tile sweep", light, o);
  std::vector<std::uint8_t> unexplained_flipped(mask.pixels.size()), unexplained_covered(mask.pixels.size());
  for (const std::size_t i : flip.unexplained) unexplained_flipped[i] = 1;
  for (const std::size_t i : cover.unexplained) unexplained_covered[i] = 1;
  // Per half: the pixels a swap leaves unexplained, and those it changes that are decided.
  HalfFlags unexplained{Table(w, h), Table(w, h)}, changed{Table(w, h), Table(w, h)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x + kTile < w; ++x) {
      if (!pairs(x, y)) continue;
      const bool coverage = at(mask, x, y) == kMaskNoSurface || at(mask, x + kTile, y) == kMaskNoSurface;
      const std::vector<std::uint8_t>& u = coverage ? unexplained_covered : unexplained_flipped;
      const std::size_t i = static_cast<std::size_t>(y * w + x);
      if (u[i]) unexplained.left.add(x, y);
      if (u[i + kTile]) unexplained.right.add(x + kTile, y);
      if (outputs::is_flag_set(decided.pixels[i])) changed.left.add(x, y);
      if (outputs::is_flag_set(decided.pixels[i + kTile])) changed.right.add(x + kTile, y);
    }
  for (Table* t : {&unexplained.left, &unexplained.right, &changed.left, &changed.right}) t->integrate();
  const std::size_t bound = compare::kLocalGlitch.densest_fail;
  const int core = compare::kCoreRadius, cluster = compare::kClusterRadius;
  // The most flags of `f` in one 9 × 9 window centred on one of them, of the tile at (tx, ty)
  // (compare_mask's densest_unexplained, densest_change).
  const auto densest = [cluster](const HalfFlags& f, int tx, int ty) {
    std::size_t most = 0;
    for (int y = ty; y < ty + kTile; ++y)
      for (int x = tx; x < tx + 2 * kTile; ++x)
        if (f.in_tile(tx, ty, x, y, x + 1, y + 1))
          most = std::max(most, static_cast<std::size_t>(f.in_tile(tx, ty, x - cluster, y - cluster, x + cluster + 1, y + cluster + 1)));
    return most;
  };
  std::vector<TilePlace> out;
  for (int ty = 0; ty + kTile <= h; ++ty) {
    outputs::throw_if_interrupted();  // SIGINT / SIGTERM: per row of places
    for (int tx = 0; tx + 2 * kTile <= w; ++tx) {
      const int x1 = tx + 2 * kTile, y1 = ty + kTile;
      // Fewer changed decided pixels in the whole tile than the bound: none in a window exceeds it.
      if (static_cast<std::size_t>(changed.in_tile(tx, ty, tx, ty, x1, y1)) <= bound) continue;
      compare::MaskMetrics m;
      m.edge_pixels = flip.metrics.edge_pixels;  // the reference's: the same for every candidate
      m.unexplained = static_cast<std::size_t>(unexplained.in_tile(tx, ty, tx, ty, x1, y1));
      // Cores: a pixel whose (2 kCoreRadius + 1)² neighbourhood is all unexplained lies that far
      // inside the tile's box (nothing outside it changes). The first is enough to FAIL (decide).
      const int full = (2 * core + 1) * (2 * core + 1);
      for (int y = ty + core; y + core < y1 && m.unexplained_core == 0; ++y)
        for (int x = tx + core; x + core < x1 && m.unexplained_core == 0; ++x)
          m.unexplained_core = unexplained.in_tile(tx, ty, x - core, y - core, x + core + 1, y + core + 1) == full;
      if (m.unexplained_core == 0 && threshold.bands) m.densest_unexplained = densest(unexplained, tx, ty);
      if (compare::decide(m, threshold).verdict == compare::Verdict::Fail) continue;
      if (densest(changed, tx, ty) > bound) out.push_back({tx, ty});  // it shows something (densest_change)
    }
  }
  return out;
}

}  // namespace shadowref::tolerance
