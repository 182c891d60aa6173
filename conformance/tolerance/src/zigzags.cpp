// zigzags.cpp — wrong pixels that no texel grid gives together (zigzags.hpp).
#include "shadowref/tolerance/zigzags.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "shadowref/compare/compare.hpp"
#include "shadowref/compare/thresholds.hpp"
#include "shadowref/outputs/interruption.hpp"
#include "shadowref/reference/causes.hpp"

namespace shadowref::tolerance {
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

// The vertices of the convex hull of `p`, given in the order of a lattice's rows (by y, then x),
// with no point twice (Andrew's monotone chain on that order; collinear points dropped): a linear
// function's least and greatest over the points are at them, so gap() over the hulls is gap() over
// the points, at a fraction of the cost.
std::vector<Vec2> hull(const std::vector<Vec2>& p) {
  if (p.size() < 3) return p;
  // The chain's turn test on points ordered by (y, x): the usual one on (x, y) with the axes swapped.
  const auto turn = [](const Vec2& o, const Vec2& a, const Vec2& b) { return (a[1] - o[1]) * (b[0] - o[0]) - (a[0] - o[0]) * (b[1] - o[1]); };
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); h[k++] = p[i++])
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; h[k++] = p[--i])
    while (k >= t && turn(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
  h.resize(k - 1);
  return h;
}

// The edge's frame at normal angle a: its normal (cos a, sin a), the edge along (−sin a, cos a).
struct EdgeFrame {
  explicit EdgeFrame(double a) : c(std::cos(a)), s(std::sin(a)) {}
  Vec2 along_and_across(const Vec2& q) const { return {-s * q[0] + c * q[1], c * q[0] + s * q[1]}; }
  Vec2 back(double e, double n) const { return {c * n - s * e, s * n + c * e}; }  // along_and_across's inverse
  EdgePoint operator()(const Pixel& p) const {
    const Vec2 es = along_and_across(p.q);
    return {es[0], es[1], p.shadowed};
  }
  double c, s;
};

// The candidate zigzags among `px` whose middle pixel is px[middle], in the frame of an edge whose
// normal points into the shadow: index triples into px, the outer pixels nearest the middle along
// the edge first.
std::vector<std::array<std::size_t, 3>> zigzags_at(const std::vector<Pixel>& px, const EdgeFrame& on_edge, std::size_t middle) {
  std::vector<std::pair<double, std::size_t>> order;  // (e, index), along the edge
  order.reserve(px.size());
  for (std::size_t i = 0; i < px.size(); ++i) order.emplace_back(on_edge(px[i]).e, i);
  std::sort(order.begin(), order.end());
  const auto at = std::find_if(order.begin(), order.end(), [&](const auto& o) { return o.second == middle; });
  const std::size_t j = static_cast<std::size_t>(at - order.begin());
  const EdgePoint m = on_edge(px[middle]);
  // The outer pixels: the other answer, on the side of the middle one that makes a zigzag.
  const auto beyond = [&](std::size_t i) {
    const EdgePoint o = on_edge(px[i]);
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
      if (no_grid_gives(on_edge(px[i]), m, on_edge(px[k]))) out.push_back({i, middle, k});
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

namespace {

// A window the check looks at: its densest point and its bounds (inclusive).
struct Window {
  int cx, cy, x0, y0, x1, y1;
};

// The windows, densest first: centred on a wrong pixel whose 9 × 9 window holds more wrong pixels
// than the local-glitch bound, half a window from any taken before, where the candidate crosses a
// row or column more often than the reference; at most kMaxZigzagWindows. `is_wrong` gets the wrong
// lit/shadowed pixels.
std::vector<Window> windows_of(const outputs::Image8& reference, const outputs::Image8& candidate, const std::vector<std::size_t>& wrong,
                               std::vector<std::uint8_t>& is_wrong) {
  const int w = candidate.width, h = candidate.height;
  is_wrong.assign(candidate.pixels.size(), 0);
  for (const std::size_t i : wrong)
    if (lit_or_shadowed(reference.pixels[i]) && lit_or_shadowed(candidate.pixels[i])) is_wrong[i] = 1;
  // Their count in every 9 × 9 window, from a summed-area table.
  std::vector<int> sum(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1), 0);
  const auto S = [&](int x, int y) -> int& { return sum[static_cast<std::size_t>(y) * static_cast<std::size_t>(w + 1) + static_cast<std::size_t>(x)]; };
  const auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x); };
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
  std::vector<Window> out;
  // The centres taken, on a grid of cells one more than half a window wide: two centres of one cell
  // are within half a window of each other, so a cell holds at most one, and a centre within half a
  // window of a new one lies in its cell or one of the eight around it. The same answer as asking
  // every centre taken, which cost a boundary's length per seed.
  constexpr int kCell = kWindowRadius / 2 + 1;
  const int cells_x = w / kCell + 1, cells_y = h / kCell + 1;
  std::vector<int> taken(static_cast<std::size_t>(cells_x) * static_cast<std::size_t>(cells_y), -1);  // the centre's index, or -1
  const auto near_taken = [&](int cx, int cy) {
    const int gx = cx / kCell, gy = cy / kCell;
    for (int v = std::max(0, gy - 1); v <= std::min(cells_y - 1, gy + 1); ++v)
      for (int u = std::max(0, gx - 1); u <= std::min(cells_x - 1, gx + 1); ++u) {
        const int t = taken[static_cast<std::size_t>(v) * static_cast<std::size_t>(cells_x) + static_cast<std::size_t>(u)];
        if (t >= 0 && std::abs(cx - t % w) <= kWindowRadius / 2 && std::abs(cy - t / w) <= kWindowRadius / 2) return true;
      }
    return false;
  };
  for (const auto& [density, centre] : seeds) {
    if (out.size() == kMaxZigzagWindows) break;
    const int cx = static_cast<int>(centre % static_cast<std::size_t>(w)), cy = static_cast<int>(centre / static_cast<std::size_t>(w));
    if (near_taken(cx, cy)) continue;
    taken[static_cast<std::size_t>(cy / kCell) * static_cast<std::size_t>(cells_x) + static_cast<std::size_t>(cx / kCell)] = cy * w + cx;
    const Window win{cx, cy, std::max(0, cx - kWindowRadius), std::max(0, cy - kWindowRadius), std::min(w - 1, cx + kWindowRadius),
                     std::min(h - 1, cy + kWindowRadius)};
    if (more_crossings(reference, candidate, win.x0, win.y0, win.x1, win.y1)) out.push_back(win);
  }
  return out;
}

// The light's plane: `dir` the way the light travels, `u` and `v` across it.
struct LightFrame {
  Vec3<double> dir, u, v;
};

// A window's pixels on the receiver plane of its centre, facing the light, with what the samples
// need of them: the declared map's texel there (its largest), their depths along the light and the
// box of their points in the light's plane.
struct OnePlane {
  Cell plane;
  std::vector<Pixel> px;
  double texel = 0, dmin = INFINITY, dmax = -INFINITY;
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
};

std::optional<OnePlane> pixels_of(const reference::CauseModel& model, std::size_t light, const outputs::CandidateDeclaration& d,
                                  const LightFrame& f, const outputs::Image8& candidate, const std::vector<std::uint8_t>& is_wrong,
                                  const Window& win) {
  const std::optional<Cell> centre = model.texel_cell(light, win.cx, win.cy, d);
  if (!centre) return std::nullopt;
  OnePlane o{*centre, {}};
  const auto at = [&](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(candidate.width) + static_cast<std::size_t>(x); };
  for (int y = win.y0; y <= win.y1; ++y)
    for (int x = win.x0; x <= win.x1; ++x) {
      if (!lit_or_shadowed(candidate.pixels[at(x, y)])) continue;
      const std::optional<Cell> c = model.texel_cell(light, x, y, d);
      if (!c || !o.plane.shares_plane(*c)) continue;
      const Vec2 q{c->p.dot(f.u), c->p.dot(f.v)};
      o.px.push_back({at(x, y), q, outputs::mask_class(candidate.pixels[at(x, y)]) == outputs::kClassShadowed, is_wrong[at(x, y)] != 0});
      o.texel = std::max(o.texel, c->texel);
      o.dmin = std::min(o.dmin, c->p.dot(f.dir));
      o.dmax = std::max(o.dmax, c->p.dot(f.dir));
      for (int k = 0; k < 2; ++k) o.lo[k] = std::min(o.lo[k], q[k]), o.hi[k] = std::max(o.hi[k], q[k]);
    }
  if (o.px.size() < 3 || !(o.texel > 0)) return std::nullopt;
  return o;
}

// What the texels within reach of a window's pixels store, sampled on a square lattice of the
// light's plane: shadowing every pixel whatever bias a correct map adds, lighting every one, or
// either (allowed only between the two kinds).
class StoredSamples {
 public:
  // nullopt where the lattice would be coarser than kMaxSamplesPerTexel.
  static std::optional<StoredSamples> sample(const reference::CauseModel& model, const scene::PreparedScene& scene, std::size_t light,
                                             const outputs::CandidateDeclaration& d, const LightFrame& f, const OnePlane& o,
                                             double reach) {
    StoredSamples s;
    s.lo_ = {o.lo[0] - reach, o.lo[1] - reach};
    const Vec2 hi{o.hi[0] + reach, o.hi[1] + reach};
    s.step_ = o.texel / kSamplesPerTexel;
    const double widest = std::max(hi[0] - s.lo_[0], hi[1] - s.lo_[1]);
    if (widest / s.step_ > static_cast<double>(kMaxSamplesPerAxis - 1)) s.step_ = widest / static_cast<double>(kMaxSamplesPerAxis - 1);
    if (s.step_ > o.texel / kMaxSamplesPerTexel) return std::nullopt;  // too wide to sample finely enough
    s.nx_ = static_cast<int>(std::floor((hi[0] - s.lo_[0]) / s.step_)) + 1;
    s.ny_ = static_cast<int>(std::floor((hi[1] - s.lo_[1]) / s.step_)) + 1;
    s.kind_.assign(static_cast<std::size_t>(s.nx_) * static_cast<std::size_t>(s.ny_), kUnasked);
    // The samples within the reach of some pixel's point (a disc of cells around each).
    const int disc = static_cast<int>(std::ceil(reach / s.step_)) + 1;
    for (const Pixel& p : o.px) {
      const int ci = static_cast<int>(std::lround((p.q[0] - s.lo_[0]) / s.step_)), cj = static_cast<int>(std::lround((p.q[1] - s.lo_[1]) / s.step_));
      for (int j = std::max(0, cj - disc); j <= std::min(s.ny_ - 1, cj + disc); ++j)
        for (int i = std::max(0, ci - disc); i <= std::min(s.nx_ - 1, ci + disc); ++i)
          if ((i - ci) * (i - ci) + (j - cj) * (j - cj) <= disc * disc) s.at(i, j) = kAsked;
    }
    // The most bias a correct map adds, in texels of a stored polygon's slope: the cause model's cap
    // for false light (kCorrectBiasMargin × twice the mask's reach) or the distance its false
    // shadows allow (the whole reach), an own texel √2 wide; and the depth format's precision (a
    // directional map's depths span about the scene).
    const double needed = std::sqrt(2.0) * std::max(reference::kCorrectBiasMargin * 2.0 *
                                                        (reference::grid_uncertainty_texels(d) +
                                                         std::min(d.filter_radius_texels, reference::kMaxMaskFilterTexels)),
                                                    1.0 + 2.0 * d.filter_radius_texels);
    const double precision = 2 * (scene.bounds[1] - scene.bounds[0]).norm() * reference::kDepthPrecision;
    const double depth_at = 0.5 * (o.dmin + o.dmax);
    for (int j = 0; j < s.ny_; ++j)
      for (int i = 0; i < s.nx_; ++i) {
        std::uint8_t& k = s.at(i, j);
        if (k == kUnasked) continue;
        const Vec2 q = s.point(i, j);
        const reference::CauseModel::StoredAlong st = model.stored_along(light, q[0] * f.u + q[1] * f.v + depth_at * f.dir);
        bool all_shadow = !st.nothing, all_light = true;
        for (const reference::CauseModel::Stored& t : st.surfaces) {
          const double depth = t.p.dot(f.dir);
          const bool own_plane = std::abs(o.plane.n.dot(t.p) - o.plane.offset) <= 1e-4 * o.texel;
          const double bias = needed * o.texel * reference::capped_tan(std::abs(t.ng.normalized().dot(f.dir))) + precision;
          all_shadow = all_shadow && !own_plane && depth + bias < o.dmin;
          all_light = all_light && (own_plane || depth >= o.dmax);
        }
        k = all_shadow ? kShadowing : all_light ? kLighting : kEither;
      }
    // A sample that may store either is allowed on the boundary alone (a ray that grazes a caster's
    // silhouette, where its walk through the caster is a matter of rounding): both kinds beside it.
    for (int j = 0; j < s.ny_; ++j)
      for (int i = 0; i < s.nx_; ++i) {
        if (s.at(i, j) != kEither) continue;
        bool sh = false, li = false;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            if (i + di < 0 || j + dj < 0 || i + di >= s.nx_ || j + dj >= s.ny_) continue;
            sh = sh || s.at(i + di, j + dj) == kShadowing;
            li = li || s.at(i + di, j + dj) == kLighting;
          }
        if (sh && li) s.at(i, j) = kBoundary;
      }
    return s;
  }

  double step() const { return step_; }

  // The range of the edge normal's angle (into the shadow) over the samples that `keeps` keeps,
  // all within the box [lo, hi] of the light's plane: a line of such a normal separates their
  // shadowing samples from their lighting ones, as the true edge's does when they lie on one
  // straight edge (nullopt: they do not, or some sample there may store either). Looked for within
  // `half` of `around` (radians).
  template <class Keeps>
  std::optional<std::pair<double, double>> separation(const Keeps& keeps, const Vec2& lo, const Vec2& hi, double around, double half) {
    sh_.clear();
    li_.clear();
    // The lattice's rows and columns that meet the box, a sample more on each side for rounding.
    const auto first = [&](double v, double origin) { return static_cast<int>(std::floor((v - origin) / step_)) - 1; };
    const auto last = [&](double v, double origin) { return static_cast<int>(std::ceil((v - origin) / step_)) + 1; };
    const int i0 = std::max(0, first(lo[0], lo_[0])), i1 = std::min(nx_ - 1, last(hi[0], lo_[0]));
    const int j0 = std::max(0, first(lo[1], lo_[1])), j1 = std::min(ny_ - 1, last(hi[1], lo_[1]));
    for (int j = j0; j <= j1; ++j)  // by rows: the order hull() takes
      for (int i = i0; i <= i1; ++i) {
        const std::uint8_t k = at(i, j);
        if (k == kUnasked || k == kAsked) continue;
        const Vec2 q = point(i, j);
        if (!keeps(q)) continue;
        if (k == kEither) return std::nullopt;
        if (k == kShadowing) sh_.push_back(q);
        if (k == kLighting) li_.push_back(q);
      }
    if (sh_.empty() || li_.empty()) return std::nullopt;
    sh_ = hull(sh_);
    li_ = hull(li_);
    const double fine = std::numbers::pi / 3600.0;  // 0.05°
    double best = -INFINITY, best_a = around;
    for (double a = around - half; a <= around + half; a += 10 * fine)
      if (const double g = gap(sh_, li_, a); g > best) best = g, best_a = a;
    if (!(best > 0)) return std::nullopt;
    double a_lo = best_a, a_hi = best_a;
    while (a_lo > best_a - std::numbers::pi && gap(sh_, li_, a_lo - fine) > 0) a_lo -= fine;
    while (a_hi < best_a + std::numbers::pi && gap(sh_, li_, a_hi + fine) > 0) a_hi += fine;
    return std::make_pair(a_lo - fine, a_hi + fine);  // a step beyond: the range's true ends lie within it
  }

 private:
  enum Kind : std::uint8_t { kUnasked, kAsked, kShadowing, kLighting, kEither, kBoundary };
  std::uint8_t& at(int i, int j) { return kind_[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i)]; }
  Vec2 point(int i, int j) const { return {lo_[0] + i * step_, lo_[1] + j * step_}; }
  Vec2 lo_{};
  double step_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint8_t> kind_;
  std::vector<Vec2> sh_, li_;  // separation()'s scratch
};

// Marks in `certified` the wrong pixels of every zigzag among o's pixels that the samples allow:
// each wrong pixel as the middle, at the edge's normal from the samples within twice `margin` of it,
// its first kTriesPerPixel triples, each certified only where the samples within `margin` of the box
// it spans are one straight edge and over the whole range of that edge's normal.
void certify(const OnePlane& o, StoredSamples& samples, double margin, std::vector<std::uint8_t>& certified) {
  const std::vector<Pixel>& px = o.px;
  for (std::size_t j = 0; j < px.size(); ++j) {
    if (!px[j].wrong) continue;
    const Vec2 at = px[j].q;
    const auto around_j = samples.separation([&](const Vec2& q) { return std::hypot(q[0] - at[0], q[1] - at[1]) <= 2 * margin; },
                                             {at[0] - 2 * margin, at[1] - 2 * margin}, {at[0] + 2 * margin, at[1] + 2 * margin},
                                             std::numbers::pi, std::numbers::pi);
    if (!around_j) continue;
    const double a = 0.5 * (around_j->first + around_j->second);
    const EdgeFrame edge(a);
    std::size_t tries = 0;
    for (const auto& t : zigzags_at(px, edge, j)) {
      if (++tries > kTriesPerPixel) break;
      // The triple's box along the edge and its normal, and the samples within reach of it: where
      // the boundary between its three pixels runs, and every texel a lookup there reads.
      double e0 = INFINITY, e1 = -INFINITY, s0 = INFINITY, s1 = -INFINITY;
      for (const std::size_t k : t) {
        const EdgePoint p = edge(px[k]);
        e0 = std::min(e0, p.e), e1 = std::max(e1, p.e), s0 = std::min(s0, p.s), s1 = std::max(s1, p.s);
      }
      const double within = margin + (e1 - e0 + s1 - s0) * std::sin(around_j->second - around_j->first);
      const auto in_box = [&](const Vec2& q) {
        const Vec2 es = edge.along_and_across(q);
        const double de = std::max({0.0, e0 - es[0], es[0] - e1}), ds = std::max({0.0, s0 - es[1], es[1] - s1});
        return std::hypot(de, ds) <= within;
      };
      // The bounds of the box's corners back in the light's plane, widened by `within`.
      Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
      for (const double e : {e0, e1})
        for (const double sv : {s0, s1}) {
          const Vec2 q = edge.back(e, sv);
          for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k] - within), hi[k] = std::max(hi[k], q[k] + within);
        }
      const auto range = samples.separation(in_box, lo, hi, a, std::numbers::pi / 36);
      if (!range) continue;
      // Certified only if it holds over the whole range of the edge's normal there.
      const auto holds_at = [&](double b) {
        const EdgeFrame on_edge(b);
        return no_grid_gives(on_edge(px[t[0]]), on_edge(px[t[1]]), on_edge(px[t[2]]));
      };
      bool holds = holds_at(range->second);
      for (double b = range->first; b < range->second && holds; b += std::numbers::pi / 3600.0) holds = holds_at(b);
      if (!holds) continue;
      for (const std::size_t k : t)
        if (px[k].wrong) certified[px[k].index] = 1;
      break;
    }
  }
}

}  // namespace

ZigzagFinding find_zigzags(const reference::CauseModel& model, const scene::PreparedScene& scene, std::size_t light,
                           const outputs::CandidateDeclaration& d, const outputs::Image8& reference,
                           const outputs::Image8& candidate, const std::vector<std::size_t>& wrong) {
  ZigzagFinding found;
  LightFrame f;
  f.dir = -scene.lights[light].head<3>().normalized();
  f.u = (std::abs(f.dir.z()) < 0.9 ? f.dir.cross(Vec3<double>(0, 0, 1)) : f.dir.cross(Vec3<double>(1, 0, 0))).normalized();
  f.v = f.dir.cross(f.u);
  std::vector<std::uint8_t> is_wrong, certified(candidate.pixels.size(), 0);
  for (const Window& win : windows_of(reference, candidate, wrong, is_wrong)) {
    outputs::throw_if_interrupted();  // SIGINT / SIGTERM: per window
    ++found.windows;
    const std::optional<OnePlane> o = pixels_of(model, light, d, f, candidate, is_wrong, win);
    if (!o) continue;
    // The texels any lookup of these pixels may read, as a distance from each pixel's point: an own
    // view's texel up to √2 wider than the fit's at the declared size (a turned view that still
    // covers the fit), its centre within half its diagonal (one fit texel), the filter's taps within
    // its radius of them along both axes (2 r fit texels); a declared normal offset moves them all.
    const Vec3<double> along = o->plane.n - o->plane.n.dot(f.dir) * f.dir;
    const double reach = (1.0 + 2.0 * d.filter_radius_texels) * o->texel + along.norm() * (d.normal_offset + d.normal_offset_texels * o->texel);
    std::optional<StoredSamples> samples = StoredSamples::sample(model, scene, light, d, f, *o, reach);
    if (!samples) continue;
    ++found.judged;
    certify(*o, *samples, reach + samples->step(), certified);  // a sample stands for the texels within half a step of it
  }
  for (std::size_t i = 0; i < certified.size(); ++i)
    if (certified[i]) found.impossible.push_back(i);
  return found;
}

}  // namespace shadowref::tolerance
