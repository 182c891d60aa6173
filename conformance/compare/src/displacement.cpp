// displacement.cpp — displaced shadows (displacement.hpp): each screen-space move undone on the
// candidate's mask, its unexplained pixels checked one by one, the change in its shadow errors
// counted on the band where a move can change anything.
#include "shadowref/compare/displacement.hpp"

#include "shadowref/outputs/interruption.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>

namespace shadowref::compare {
namespace {

// The mask's three values (outputs/image.hpp); the comparison refuses any other before asking.
constexpr std::uint8_t kShadowed = outputs::kMaskShadowed, kNoSurface = outputs::kMaskNoSurface, kLit = outputs::kMaskLit;

// The candidate's class at pixel i = (x, y) with `move` undone: translated back by (dx, dy), or its
// shadows shrunk back (grow > 0) or grown back (grow < 0) by |grow| px within a square — a surface
// pixel takes `into` where any pixel within |grow| px has it. A translated pixel keeps its own
// class where it or the pixel it would take from is no surface.
struct Undo {
  const std::vector<std::uint8_t>& cand;  // the candidate's mask values
  int w, h;
  std::uint8_t operator()(const ShadowMove& m, std::size_t i) const {
    const std::uint8_t c = cand[i];
    if (c == kNoSurface) return c;
    const int x = static_cast<int>(i % static_cast<std::size_t>(w)), y = static_cast<int>(i / static_cast<std::size_t>(w));
    if (m.grow == 0) {
      const int u = x + m.dx, v = y + m.dy;
      if (u < 0 || v < 0 || u >= w || v >= h) return c;
      const std::uint8_t from = cand[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)];
      return from == kNoSurface ? c : from;
    }
    // Grown shadows are undone by growing the light, shrunk ones by growing the shadow.
    const std::uint8_t into = m.grow > 0 ? kLit : kShadowed;
    if (c == into) return c;
    const int k = std::abs(m.grow);
    for (int v = std::max(0, y - k); v <= std::min(h - 1, y + k); ++v)
      for (int u = std::max(0, x - k); u <= std::min(w - 1, x + k); ++u)
        if (cand[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)] == into) return into;
    return c;
  }
};

// Whether class `c` at pixel i is a judged shadow error (lit against shadowed; judged: decided, or,
// under the scene's invariant, a false shadow where the reference is lit).
inline bool shadow_error(const std::vector<std::uint8_t>& ref, const outputs::Image8& decided, bool invariant,
                         std::size_t i, std::uint8_t c) {
  const std::uint8_t r = outputs::nearest_mask_value(ref[i]);
  if (r == kNoSurface || c == kNoSurface || r == c) return false;
  return outputs::is_flag_set(decided.pixels[i]) || (invariant && r == kLit && c == kShadowed);
}

// The pixels a move of at most kReach px can change: those within kReach px (a square) of a pair of
// 4-neighbours of different values. Everywhere else the moved mask is the mask, so each move is
// judged on this band alone. One pass over the image finds the pairs; the band is marked around
// them only (a calloc'd image: its untouched pages cost nothing).
constexpr int kReach = 2;
std::vector<std::size_t> near_boundaries(const std::vector<std::uint8_t>& cand, int w, int h) {
  const std::size_t stride = static_cast<std::size_t>(w);
  std::vector<std::size_t> edges;
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* row = cand.data() + static_cast<std::size_t>(y) * stride;
    const std::uint8_t* below = y + 1 < h ? row + stride : row;
    for (int x = 0; x < w; ++x)
      if ((x + 1 < w && row[x] != row[x + 1]) || row[x] != below[x])
        edges.push_back(static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x));
  }
  std::unique_ptr<std::uint8_t, void (*)(void*)> marked(static_cast<std::uint8_t*>(std::calloc(cand.size() + 1, 1)), std::free);
  if (!marked) throw std::bad_alloc();
  std::vector<std::size_t> band;
  for (const std::size_t e : edges) {
    // The pair's other pixel is right of or below e: the square from e reaches it, one more px.
    const int x = static_cast<int>(e % stride), y = static_cast<int>(e / stride);
    for (int v = std::max(0, y - kReach); v <= std::min(h - 1, y + kReach + 1); ++v)
      for (int u = std::max(0, x - kReach); u <= std::min(w - 1, x + kReach + 1); ++u) {
        const std::size_t i = static_cast<std::size_t>(v) * stride + static_cast<std::size_t>(u);
        if (!marked.get()[i]) marked.get()[i] = 1, band.push_back(i);
      }
  }
  return band;
}

}  // namespace

std::string describe(const ShadowMove& m) {
  if (m.grow != 0)
    return std::string("shadows ") + (m.grow > 0 ? "grown" : "shrunk") + " by " + std::to_string(std::abs(m.grow)) + " px";
  std::string s = "shadows moved";
  const auto part = [&s](int d, const char* plus, const char* minus) {
    if (d == 0) return;
    s += " " + std::to_string(std::abs(d)) + " px " + (d > 0 ? plus : minus);
  };
  part(m.dx, "right", "left");
  if (m.dx != 0 && m.dy != 0) s += " and";
  part(m.dy, "down", "up");
  return s;
}

Displacement find_displacement(const outputs::Image8& reference, const outputs::Image8& decided,
                               const outputs::Image8& candidate, bool invariant,
                               const std::vector<std::size_t>& unexplained, std::size_t shadow_errors) {
  Displacement best;
  best.wrong_before = best.wrong_after = shadow_errors;
  if (unexplained.empty()) return best;
  const std::vector<std::uint8_t>& ref = reference.pixels;
  const std::vector<std::uint8_t>& cand = candidate.pixels;
  const Undo undo{cand, reference.width, reference.height};
  const std::vector<std::size_t> band = near_boundaries(cand, reference.width, reference.height);
  std::vector<ShadowMove> moves;
  for (int dy = -kReach; dy <= kReach; ++dy)
    for (int dx = -kReach; dx <= kReach; ++dx)
      if (dx != 0 || dy != 0) moves.push_back({dx, dy, 0});
  for (const int g : {1, 2, -1, -2}) moves.push_back({0, 0, g});
  for (const ShadowMove& m : moves) {
    outputs::throw_if_interrupted();  // SIGINT / SIGTERM: per move tried
    std::size_t fixed = 0;
    for (const std::size_t i : unexplained) fixed += undo(m, i) == outputs::nearest_mask_value(ref[i]);
    if (fixed <= best.fixed_unexplained) continue;
    // The moved mask's shadow errors: the mask's, changed within the band only.
    std::ptrdiff_t change = 0;
    for (const std::size_t i : band) {
      const std::uint8_t moved = undo(m, i);
      if (moved != cand[i])
        change += static_cast<std::ptrdiff_t>(shadow_error(ref, decided, invariant, i, moved)) -
                  static_cast<std::ptrdiff_t>(shadow_error(ref, decided, invariant, i, cand[i]));
    }
    if (change >= 0) continue;  // the mask moved back agrees no better
    best.move = m;
    best.fixed_unexplained = fixed;
    best.wrong_after = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(best.wrong_before) + change);
  }
  return best;
}

}  // namespace shadowref::compare
