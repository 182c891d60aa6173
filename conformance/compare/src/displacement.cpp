// displacement.cpp — displaced shadows (displacement.hpp): each screen-space move undone on the
// candidate's classes, its shadow errors counted on the judged pixels, its unexplained pixels
// checked one by one.
#include "shadowref/compare/displacement.hpp"

#include <algorithm>
#include <cstdint>

namespace shadowref::compare {
namespace {

enum Class : std::uint8_t { kShadowed = 0, kNoSurface = 1, kLit = 2 };
inline std::uint8_t classify(std::uint8_t v) { return static_cast<std::uint8_t>((v >= 64) + (v >= 192)); }

std::vector<std::uint8_t> classes(const outputs::Image8& m) {
  std::vector<std::uint8_t> c(m.pixels.size());
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = classify(m.pixels[i]);
  return c;
}

// The candidate's classes with `move` undone: translated back by (dx, dy), or its shadows shrunk
// back (grow > 0) or grown back (grow < 0) by |grow| px within a square — a surface pixel takes
// `into` where any surface pixel within |grow| px has it (separable: rows, then columns).
void undo(const std::vector<std::uint8_t>& cand, int w, int h, const ShadowMove& move, std::vector<std::uint8_t>& out) {
  out = cand;
  if (move.grow == 0) {
    for (int y = 0; y < h; ++y) {
      const int v = y + move.dy;
      if (v < 0 || v >= h) continue;
      for (int x = 0; x < w; ++x) {
        const int u = x + move.dx;
        if (u < 0 || u >= w) continue;
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        const std::uint8_t from = cand[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)];
        if (cand[i] != kNoSurface && from != kNoSurface) out[i] = from;
      }
    }
    return;
  }
  // Grown shadows are undone by growing the light, shrunk ones by growing the shadow.
  const std::uint8_t into = move.grow > 0 ? kLit : kShadowed;
  const int k = std::abs(move.grow);
  const std::size_t n = cand.size();
  std::vector<std::uint8_t> has(n), rows(n, 0);
  for (std::size_t i = 0; i < n; ++i) has[i] = cand[i] == into;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t any = 0;
      for (int u = std::max(0, x - k); u <= std::min(w - 1, x + k) && !any; ++u)
        any = has[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)];
      rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = any;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      if (cand[i] == kNoSurface || cand[i] == into) continue;
      bool any = false;
      for (int v = std::max(0, y - k); v <= std::min(h - 1, y + k) && !any; ++v)
        any = rows[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] != 0;
      if (any) out[i] = into;
    }
}

// Shadow errors (lit against shadowed) of `cand` on the judged pixels.
std::size_t shadow_errors(const std::vector<std::uint8_t>& ref, const outputs::Image8& decided,
                          const std::vector<std::uint8_t>& cand, bool invariant) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const std::uint8_t r = ref[i], c = cand[i];
    if (r == kNoSurface || c == kNoSurface || r == c) continue;
    const bool judged = decided.pixels[i] >= 128 || (invariant && r == kLit && c == kShadowed);
    n += judged;
  }
  return n;
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
                               const std::vector<std::size_t>& unexplained) {
  Displacement best;
  const std::vector<std::uint8_t> ref = classes(reference), cand = classes(candidate);
  best.wrong_before = best.wrong_after = shadow_errors(ref, decided, cand, invariant);
  if (unexplained.empty()) return best;
  std::vector<ShadowMove> moves;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      if (dx != 0 || dy != 0) moves.push_back({dx, dy, 0});
  for (const int g : {1, 2, -1, -2}) moves.push_back({0, 0, g});
  std::vector<std::uint8_t> moved;
  for (const ShadowMove& m : moves) {
    undo(cand, reference.width, reference.height, m, moved);
    std::size_t fixed = 0;
    for (const std::size_t i : unexplained) fixed += moved[i] == ref[i];
    if (fixed <= best.fixed_unexplained) continue;
    const std::size_t after = shadow_errors(ref, decided, moved, invariant);
    if (after >= best.wrong_before) continue;  // the mask moved back agrees no better
    best.move = m;
    best.fixed_unexplained = fixed;
    best.wrong_after = after;
  }
  return best;
}

}  // namespace shadowref::compare
