// zigzags.cpp — wrong pixels that no texel grid gives together (zigzags.hpp).
#include "shadowref/conform/zigzags.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "shadowref/compare/compare.hpp"
#include "shadowref/compare/thresholds.hpp"
#include "shadowref/reference/causes.hpp"

namespace shadowref::conform {
namespace {

using Cell = reference::CauseModel::TexelCell;
using Vec2 = std::array<double, 2>;

constexpr int kWindowRadius = 10;        // a window is 21 × 21 px around its densest point
constexpr double kSamplesPerTexel = 4;   // light-plane samples per texel of the declared map
constexpr double kMaxSamplesPerTexel = 2;  // ... no coarser than this, else the window is left alone
constexpr std::size_t kMaxSamplesPerAxis = 128;
constexpr std::size_t kNearestOthers = 32;  // outer pixels tried on each side of a middle one
constexpr std::size_t kTriesPerPixel = 8;   // triples checked in full per middle pixel

bool lit_or_shadowed(std::uint8_t v) {
  const std::uint8_t c = outputs::mask_class(v);
  return c == outputs::kClassLit || c == outputs::kClassShadowed;
}

// Lit/shadowed changes between consecutive surface pixels of one row (dx = 1) or column of `m`
// within [x0, x1] × [y0, y1].
int changes(const outputs::Image8& m, int x, int y, int dx, int dy, int steps) {
  int n = 0, last = -1;
  for (int i = 0; i < steps; ++i, x += dx, y += dy) {
    const std::uint8_t c = outputs::mask_class(m.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(m.width) + static_cast<std::size_t>(x)]);
    if (c == outputs::kClassNoSurface) continue;
    n += last >= 0 && c != last;
    last = c;
  }
  return n;
}

// Whether the candidate crosses some row or column of the window more often than the reference.
bool more_crossings(const outputs::Image8& ref, const outputs::Image8& cand, int x0, int y0, int x1, int y1) {
  for (int y = y0; y <= y1; ++y)
    if (changes(cand, x0, y, 1, 0, x1 - x0 + 1) > changes(ref, x0, y, 1, 0, x1 - x0 + 1)) return true;
  for (int x = x0; x <= x1; ++x)
    if (changes(cand, x, y0, 0, 1, y1 - y0 + 1) > changes(ref, x, y0, 0, 1, y1 - y0 + 1)) return true;
  return false;
}

struct Pixel {
  std::size_t index;
  Vec2 q;  // in the light's plane
  bool shadowed, wrong;
};

// The gap between the shadowing and the lighting samples along the normal at angle `a` (radians):
// positive where a line of that normal separates them.
double gap(const std::vector<Vec2>& shadow, const std::vector<Vec2>& lit, double a) {
  const double c = std::cos(a), s = std::sin(a);
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec2& p : shadow) lo = std::min(lo, c * p[0] + s * p[1]);
  for (const Vec2& p : lit) hi = std::max(hi, c * p[0] + s * p[1]);
  return lo - hi;
}

// The vertices of the convex hull of `p` (Andrew's monotone chain; collinear points dropped): a
// linear function's least and greatest over the points are at them, so gap() over the hulls is
// gap() over the points, at a fraction of the cost.
std::vector<Vec2> hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); };
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); h[k++] = p[i++])
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; h[k++] = p[--i])
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
  h.resize(k - 1);
  return h;
}

EdgePoint on_edge(const Pixel& p, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {-s * p.q[0] + c * p.q[1], c * p.q[0] + s * p.q[1], p.shadowed};
}

// The candidate zigzags among `px` whose middle pixel is px[middle], for the edge normal at angle
// `a` (into the shadow): index triples into px, the outer pixels nearest the middle along the edge
// first.
std::vector<std::array<std::size_t, 3>> zigzags_at(const std::vector<Pixel>& px, double a, std::size_t middle) {
  std::vector<std::pair<double, std::size_t>> order;  // (e, index), along the edge
  order.reserve(px.size());
  for (std::size_t i = 0; i < px.size(); ++i) order.emplace_back(on_edge(px[i], a).e, i);
  std::sort(order.begin(), order.end());
  const auto at = std::find_if(order.begin(), order.end(), [&](const auto& o) { return o.second == middle; });
  const std::size_t j = static_cast<std::size_t>(at - order.begin());
  const EdgePoint m = on_edge(px[middle], a);
  // The outer pixels: the other answer, on the side of the middle one that makes a zigzag.
  const auto beyond = [&](std::size_t i) {
    const EdgePoint o = on_edge(px[i], a);
    return o.shadowed != m.shadowed && (m.shadowed ? o.s > m.s : o.s < m.s);
  };
  std::vector<std::size_t> left, right;
  for (std::size_t i = j; i-- > 0 && left.size() < kNearestOthers;)
    if (beyond(order[i].second)) left.push_back(order[i].second);
  for (std::size_t k = j + 1; k < order.size() && right.size() < kNearestOthers; ++k)
    if (beyond(order[k].second)) right.push_back(order[k].second);
  std::vector<std::array<std::size_t, 3>> out;
  for (const std::size_t i : left)
    for (const std::size_t k : right)
      if (no_grid_gives(on_edge(px[i], a), m, on_edge(px[k], a))) out.push_back({i, middle, k});
  return out;
}

}  // namespace

bool no_grid_gives(const EdgePoint& first, const EdgePoint& middle, const EdgePoint& last) {
  if (!(first.e < middle.e && middle.e < last.e) || first.shadowed != last.shadowed || first.shadowed == middle.shadowed) return false;
  // How far the middle lies past each outer point, toward where its answer does not belong.
  const double d1 = middle.shadowed ? first.s - middle.s : middle.s - first.s;
  const double d2 = middle.shadowed ? last.s - middle.s : middle.s - last.s;
  if (!(d1 > 0 && d2 > 0)) return false;
  // Down by d1 along one axis's pieces (slope −cot x) and back up by d2 along the other's (slope
  // tan x) takes d1 tan x + d2 cot x >= 2 sqrt(d1 d2) along the edge, whatever the grid's turn x.
  return last.e - first.e < 2.0 * std::sqrt(d1 * d2);
}

bool zigzags_apply(const scene::PreparedScene& scene, std::size_t light, const outputs::TechniqueName* technique,
                   const outputs::CandidateDeclaration& d) {
  return light < scene.lights.size() && scene.lights[light].w() == 0 && technique && !technique->cascaded &&
         (technique->family == outputs::TechniqueFamily::ShadowMap || technique->family == outputs::TechniqueFamily::ShadowMapPcf) &&
         d.sampling == outputs::Sampling::Grid && d.light_views != outputs::LightViews::Declared;
}

ZigzagFinding find_zigzags(const reference::CauseModel& model, const scene::PreparedScene& scene, std::size_t light,
                           const outputs::CandidateDeclaration& d, const outputs::Image8& reference,
                           const outputs::Image8& candidate, const std::vector<std::size_t>& wrong) {
  ZigzagFinding found;
  const int w = candidate.width, h = candidate.height;
  const auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x); };
  // The wrong lit/shadowed pixels and their count in every 9 × 9 window (a summed-area table).
  std::vector<std::uint8_t> is_wrong(candidate.pixels.size(), 0);
  for (const std::size_t i : wrong)
    if (lit_or_shadowed(reference.pixels[i]) && lit_or_shadowed(candidate.pixels[i])) is_wrong[i] = 1;
  std::vector<int> sum(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1), 0);
  const auto S = [&](int x, int y) -> int& { return sum[static_cast<std::size_t>(y) * static_cast<std::size_t>(w + 1) + static_cast<std::size_t>(x)]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) S(x + 1, y + 1) = S(x, y + 1) + S(x + 1, y) - S(x, y) + is_wrong[at(x, y)];
  const int r = compare::kClusterRadius;
  std::vector<std::pair<int, std::size_t>> seeds;  // (wrong in the 9 × 9 window, centre)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!is_wrong[at(x, y)]) continue;
      const int x0 = std::max(0, x - r), y0 = std::max(0, y - r), x1 = std::min(w, x + r + 1), y1 = std::min(h, y + r + 1);
      const int n = S(x1, y1) - S(x0, y1) - S(x1, y0) + S(x0, y0);
      if (static_cast<std::size_t>(n) > compare::kLocalGlitch.densest_fail) seeds.emplace_back(n, at(x, y));
    }
  std::sort(seeds.begin(), seeds.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });

  const Vec3<double> dir = -scene.lights[light].head<3>().normalized();  // the way the light travels
  const Vec3<double> u = (std::abs(dir.z()) < 0.9 ? dir.cross(Vec3<double>(0, 0, 1)) : dir.cross(Vec3<double>(1, 0, 0))).normalized();
  const Vec3<double> v = dir.cross(u);
  const double extent = (scene.bounds[1] - scene.bounds[0]).norm();
  const double precision = 2 * extent * reference::kDepthPrecision;  // a directional map's depths span about the scene
  std::vector<std::pair<int, int>> taken;
  std::vector<std::uint8_t> certified(candidate.pixels.size(), 0);

  for (const auto& [density, centre] : seeds) {
    if (found.windows == kMaxZigzagWindows) break;
    const int cx = static_cast<int>(centre % static_cast<std::size_t>(w)), cy = static_cast<int>(centre / static_cast<std::size_t>(w));
    bool near = false;
    for (const auto& [tx, ty] : taken) near = near || (std::abs(cx - tx) <= kWindowRadius / 2 && std::abs(cy - ty) <= kWindowRadius / 2);
    if (near) continue;
    taken.emplace_back(cx, cy);
    const int x0 = std::max(0, cx - kWindowRadius), y0 = std::max(0, cy - kWindowRadius);
    const int x1 = std::min(w - 1, cx + kWindowRadius), y1 = std::min(h - 1, cy + kWindowRadius);
    if (!more_crossings(reference, candidate, x0, y0, x1, y1)) continue;
    ++found.windows;

    // The receiver plane: the centre's; the window's pixels on it, facing the light.
    const std::optional<Cell> plane = model.texel_cell(light, cx, cy, d);
    if (!plane) continue;
    std::vector<Pixel> px;
    double texel = 0, dmin = INFINITY, dmax = -INFINITY;
    Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        if (!lit_or_shadowed(candidate.pixels[at(x, y)])) continue;
        const std::optional<Cell> c = model.texel_cell(light, x, y, d);
        if (!c || !plane->shares_plane(*c)) continue;
        const Vec2 q{c->p.dot(u), c->p.dot(v)};
        px.push_back({at(x, y), q, outputs::mask_class(candidate.pixels[at(x, y)]) == outputs::kClassShadowed, is_wrong[at(x, y)] != 0});
        texel = std::max(texel, c->texel);
        dmin = std::min(dmin, c->p.dot(dir));
        dmax = std::max(dmax, c->p.dot(dir));
        for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
      }
    if (px.size() < 3 || !(texel > 0)) continue;

    // The texels any lookup of these pixels may read, as a distance from each pixel's point: an own
    // view's texel up to √2 wider than the fit's at the declared size (a turned view that still
    // covers the fit), its centre within half its diagonal (one fit texel), the filter's taps within
    // its radius of them along both axes (2 r fit texels); a declared normal offset moves them all.
    const Vec3<double> along = plane->n - plane->n.dot(dir) * dir;
    const double reach = (1.0 + 2.0 * d.filter_radius_texels) * texel + along.norm() * (d.normal_offset + d.normal_offset_texels * texel);
    for (int k = 0; k < 2; ++k) lo[k] -= reach, hi[k] += reach;
    double step = texel / kSamplesPerTexel;
    const double widest = std::max(hi[0] - lo[0], hi[1] - lo[1]);
    if (widest / step > static_cast<double>(kMaxSamplesPerAxis - 1)) step = widest / static_cast<double>(kMaxSamplesPerAxis - 1);
    if (step > texel / kMaxSamplesPerTexel) continue;  // too wide to sample finely enough
    // The samples within the reach of some pixel's point (a disc of cells around each).
    const int nx = static_cast<int>(std::floor((hi[0] - lo[0]) / step)) + 1, ny = static_cast<int>(std::floor((hi[1] - lo[1]) / step)) + 1;
    const auto cell_at = [nx](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i); };
    enum Sample : std::uint8_t { kUnasked, kAsked, kShadowing, kLighting, kEither, kBoundary };
    std::vector<std::uint8_t> sample(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), kUnasked);
    const int disc = static_cast<int>(std::ceil(reach / step)) + 1;
    for (const Pixel& p : px) {
      const int ci = static_cast<int>(std::lround((p.q[0] - lo[0]) / step)), cj = static_cast<int>(std::lround((p.q[1] - lo[1]) / step));
      for (int j = std::max(0, cj - disc); j <= std::min(ny - 1, cj + disc); ++j)
        for (int i = std::max(0, ci - disc); i <= std::min(nx - 1, ci + disc); ++i)
          if ((i - ci) * (i - ci) + (j - cj) * (j - cj) <= disc * disc) sample[cell_at(i, j)] = kAsked;
    }
    // What each sample's texel stores, for every window pixel: shadowing whatever bias a correct map
    // adds, lighting whatever bias, or either. The most a correct map adds, in texels of a stored
    // polygon's slope: the cause model's cap for false light (kCorrectBiasMargin × twice the mask's
    // reach) or the distance its false shadows allow (the whole reach), an own texel √2 wide.
    const double needed = std::sqrt(2.0) * std::max(reference::kCorrectBiasMargin * 2.0 *
                                                        (reference::grid_uncertainty_texels(d) +
                                                         std::min(d.filter_radius_texels, reference::kMaxMaskFilterTexels)),
                                                    1.0 + 2.0 * d.filter_radius_texels);
    const double depth_at = 0.5 * (dmin + dmax);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::uint8_t& k = sample[cell_at(i, j)];
        if (k == kUnasked) continue;
        const double a = lo[0] + i * step, b = lo[1] + j * step;
        const reference::CauseModel::StoredAlong st = model.stored_along(light, a * u + b * v + depth_at * dir);
        bool all_shadow = !st.nothing, all_light = true;
        for (const reference::CauseModel::Stored& t : st.surfaces) {
          const double depth = t.p.dot(dir);
          const bool own_plane = std::abs(plane->n.dot(t.p) - plane->offset) <= 1e-4 * texel;
          const double bias = needed * texel * reference::capped_tan(std::abs(t.ng.normalized().dot(dir))) + precision;
          all_shadow = all_shadow && !own_plane && depth + bias < dmin;
          all_light = all_light && (own_plane || depth >= dmax);
        }
        k = all_shadow ? kShadowing : all_light ? kLighting : kEither;
      }
    // A sample that may store either is allowed on the boundary alone (a ray that grazes a caster's
    // silhouette, where its walk through the caster is a matter of rounding): both kinds beside it.
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (sample[cell_at(i, j)] != kEither) continue;
        bool sh = false, li = false;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            if (i + di < 0 || j + dj < 0 || i + di >= nx || j + dj >= ny) continue;
            sh = sh || sample[cell_at(i + di, j + dj)] == kShadowing;
            li = li || sample[cell_at(i + di, j + dj)] == kLighting;
          }
        if (sh && li) sample[cell_at(i, j)] = kBoundary;
      }
    ++found.judged;
    // The range of the edge normal's angle (into the shadow) over the samples that `near` keeps: a
    // line of such a normal separates their shadowing samples from their lighting ones, as the
    // true edge's does when they lie on one straight edge (nullopt: they do not, or some sample
    // there may store either). Looked for within `half` of `around` (radians).
    std::vector<Vec2> sh, li;
    const auto separation = [&](const auto& keeps, double around, double half) -> std::optional<std::pair<double, double>> {
      sh.clear();
      li.clear();
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const std::uint8_t k = sample[cell_at(i, j)];
          if (k == kUnasked || k == kAsked) continue;
          const Vec2 q{lo[0] + i * step, lo[1] + j * step};
          if (!keeps(q)) continue;
          if (k == kEither) return std::nullopt;
          if (k == kShadowing) sh.push_back(q);
          if (k == kLighting) li.push_back(q);
        }
      if (sh.empty() || li.empty()) return std::nullopt;
      sh = hull(std::move(sh));
      li = hull(std::move(li));
      const double fine = std::numbers::pi / 3600.0;  // 0.05°
      double best = -INFINITY, best_a = around;
      for (double a = around - half; a <= around + half; a += 10 * fine)
        if (const double g = gap(sh, li, a); g > best) best = g, best_a = a;
      if (!(best > 0)) return std::nullopt;
      double a_lo = best_a, a_hi = best_a;
      while (a_lo > best_a - std::numbers::pi && gap(sh, li, a_lo - fine) > 0) a_lo -= fine;
      while (a_hi < best_a + std::numbers::pi && gap(sh, li, a_hi + fine) > 0) a_hi += fine;
      return std::make_pair(a_lo - fine, a_hi + fine);  // a step beyond: the range's true ends lie within it
    };
    const double margin = reach + step;  // a sample stands for the texels within half a step of it
    for (std::size_t j = 0; j < px.size(); ++j) {
      if (!px[j].wrong) continue;
      // The edge's normal where j's lookups read: from the samples within twice its reach.
      const auto around_j = separation(
          [&](const Vec2& q) { return std::hypot(q[0] - px[j].q[0], q[1] - px[j].q[1]) <= 2 * margin; }, std::numbers::pi,
          std::numbers::pi);
      if (!around_j) continue;
      const double a = 0.5 * (around_j->first + around_j->second);
      std::size_t tries = 0;
      for (const auto& t : zigzags_at(px, a, j)) {
        if (++tries > kTriesPerPixel) break;
        // The triple's box along the edge and its normal, and the samples within reach of it: where
        // the boundary between its three pixels runs, and every texel a lookup there reads.
        const double c = std::cos(a), sn = std::sin(a);
        double e0 = INFINITY, e1 = -INFINITY, s0 = INFINITY, s1 = -INFINITY;
        for (const std::size_t k : t) {
          const double e = -sn * px[k].q[0] + c * px[k].q[1], sv = c * px[k].q[0] + sn * px[k].q[1];
          e0 = std::min(e0, e), e1 = std::max(e1, e), s0 = std::min(s0, sv), s1 = std::max(s1, sv);
        }
        const auto in_box = [&](const Vec2& q) {
          const double e = -sn * q[0] + c * q[1], sv = c * q[0] + sn * q[1];
          const double de = std::max({0.0, e0 - e, e - e1}), ds = std::max({0.0, s0 - sv, sv - s1});
          return std::hypot(de, ds) <= margin + (e1 - e0 + s1 - s0) * std::sin(around_j->second - around_j->first);
        };
        const auto range = separation(in_box, a, std::numbers::pi / 36);
        if (!range) continue;
        // Certified only if it holds over the whole range of the edge's normal there.
        const auto holds_at = [&](double b) { return no_grid_gives(on_edge(px[t[0]], b), on_edge(px[t[1]], b), on_edge(px[t[2]], b)); };
        bool holds = holds_at(range->second);
        for (double b = range->first; b < range->second && holds; b += std::numbers::pi / 3600.0) holds = holds_at(b);
        if (!holds) continue;
        for (const std::size_t k : t)
          if (px[k].wrong) certified[px[k].index] = 1;
        break;
      }
    }
  }
  for (std::size_t i = 0; i < certified.size(); ++i)
    if (certified[i]) found.impossible.push_back(i);
  return found;
}

}  // namespace shadowref::conform
