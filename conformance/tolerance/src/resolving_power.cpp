// resolving_power.cpp — the probes of resolving_power.hpp: the reference's own masks with one
// blatant error each, judged as the candidate was.
#include "shadowref/tolerance/resolving_power.hpp"

#include "shadowref/record/case_record.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>
#include <utility>
#include <vector>

#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/interruption.hpp"
#include "tile_sweep.hpp"

namespace shadowref::tolerance {
namespace {

using outputs::Image8;
using outputs::kMaskLit;
using outputs::kMaskNoSurface;
using outputs::kMaskShadowed;

std::uint8_t& at(Image8& m, int x, int y) { return m.pixels[static_cast<std::size_t>(y * m.width + x)]; }
std::uint8_t at(const Image8& m, int x, int y) { return m.pixels[static_cast<std::size_t>(y * m.width + x)]; }

// The shadows grown (`grow`) or shrunk by 1 px: a surface pixel takes `grow ? shadowed : lit` when
// a surface pixel of its 3 × 3 neighbourhood has it.
Image8 morphed(const Image8& was, bool grow) {
  Image8 m = was;
  const std::uint8_t into = grow ? kMaskShadowed : kMaskLit;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      if (at(was, x, y) == kMaskNoSurface) continue;
      for (int v = std::max(0, y - 1); v <= std::min(m.height - 1, y + 1); ++v)
        for (int u = std::max(0, x - 1); u <= std::min(m.width - 1, x + 1); ++u)
          if (at(was, u, v) == into) at(m, x, y) = into;
    }
  return m;
}

struct ProbeSpec {
  ProbeKind kind;
  std::string name;
  int dx = 0, dy = 0;  // a shift's
  int rank = 0;        // a tile's place (swapped_tile)
};

std::vector<ProbeSpec> probe_specs() {
  std::vector<ProbeSpec> out;
  constexpr std::array<std::pair<int, int>, 8> kDirections{{{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};
  const auto words = [](int dx, int dy) {
    std::string w = dx > 0 ? "right" : dx < 0 ? "left" : "";
    if (dy) w += std::string(w.empty() ? "" : " and ") + (dy > 0 ? "down" : "up");
    return w;
  };
  for (const int n : {1, 2})
    for (const auto& [dx, dy] : kDirections)
      out.push_back({n == 1 ? ProbeKind::Shift1 : ProbeKind::Shift2,
                     "shifted " + std::to_string(n) + " px " + words(dx, dy), n * dx, n * dy});
  out.push_back({ProbeKind::Grown1, "grown 1 px"});
  out.push_back({ProbeKind::Shrunk1, "shrunk 1 px"});
  static_assert(kBusiestTilePlaces == 3);
  for (const auto& [rank, where] : {std::pair{0, "busiest"}, {1, "second busiest"}, {2, "third busiest"}})
    out.push_back({ProbeKind::Tile8, std::string("an 8x8 tile swapped at the ") + where + " place", 0, 0, rank});
  return out;
}

// `mask` (whose tile places are `places`) with the error of probe `p`.
Image8 probed(const Image8& mask, const std::vector<TilePlace>& places, const ProbeSpec& p) {
  switch (p.kind) {
    case ProbeKind::Shift1:
    case ProbeKind::Shift2: return shifted(mask, p.dx, p.dy);
    case ProbeKind::Grown1: return morphed(mask, true);
    case ProbeKind::Shrunk1: return morphed(mask, false);
    case ProbeKind::Tile8:
      return static_cast<std::size_t>(p.rank) < places.size() ? swapped_tile_at(mask, places[static_cast<std::size_t>(p.rank)]) : mask;
  }
  return mask;
}

constexpr std::array<ProbeKind, 5> kKinds{ProbeKind::Shift1, ProbeKind::Shift2, ProbeKind::Grown1, ProbeKind::Shrunk1,
                                          ProbeKind::Tile8};

}  // namespace

Image8 shifted(const Image8& was, int dx, int dy) {
  Image8 m = was;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const int u = x - dx, v = y - dy;
      if (u < 0 || v < 0 || u >= m.width || v >= m.height) continue;
      if (at(was, x, y) != kMaskNoSurface && at(was, u, v) != kMaskNoSurface) at(m, x, y) = at(was, u, v);
    }
  return m;
}

std::vector<TilePlace> tile_places(const Image8& mask, std::size_t count) {
  // Each window of the 4-px lattice: its top-left corner and the pixels its swap changes (twice the
  // pairs that differ).
  struct Window {
    int x, y, changes;
    long nearest = std::numeric_limits<long>::max();  // squared distance to the nearest place taken
  };
  std::vector<Window> windows;
  for (int y = 0; y + 8 <= mask.height; y += 4)
    for (int x = 0; x + 16 <= mask.width; x += 4) {
      int differ = 0;
      for (int v = 0; v < 8; ++v)
        for (int u = 0; u < 8; ++u) differ += at(mask, x + u, y + v) != at(mask, x + u + 8, y + v);
      windows.push_back({x, y, 2 * differ});
    }
  std::vector<TilePlace> places;
  const auto near_taken = [&](const Window& w) {
    for (const TilePlace& p : places)
      if (std::abs(w.x - p.x) < 16 && std::abs(w.y - p.y) < 16) return true;
    return false;
  };
  const auto take = [&](const Window& w) {
    places.push_back({w.x, w.y});
    for (Window& o : windows) {
      const long dx = o.x - w.x, dy = o.y - w.y;
      o.nearest = std::min(o.nearest, dx * dx + dy * dy);
    }
  };
  // The busiest places first: where a swap changes most pixels (the first best kept on ties).
  while (places.size() < std::min<std::size_t>(count, kBusiestTilePlaces)) {
    const Window* best = nullptr;
    for (const Window& w : windows)
      if (!near_taken(w) && (!best || w.changes > best->changes)) best = &w;
    if (!best) return places;  // no place left
    take(*best);
  }
  // Then along the rest of the boundary: the window that shows something (more changes than the
  // local-glitch bound) farthest from every place taken, the busier kept on ties.
  while (places.size() < count) {
    const Window* best = nullptr;
    for (const Window& w : windows)
      if (w.changes > static_cast<int>(compare::kLocalGlitch.densest_fail) && !near_taken(w) &&
          (!best || w.nearest > best->nearest || (w.nearest == best->nearest && w.changes > best->changes)))
        best = &w;
    if (!best) break;
    take(*best);
  }
  return places;
}

Image8 swapped_tile_at(const Image8& was, TilePlace p) {
  Image8 m = was;
  for (int v = 0; v < 8; ++v)
    for (int u = 0; u < 8; ++u) std::swap(at(m, p.x + u, p.y + v), at(m, p.x + u + 8, p.y + v));
  return m;
}

Image8 swapped_tile(const Image8& was, int rank) {
  const std::vector<TilePlace> places = tile_places(was, static_cast<std::size_t>(rank) + 1);
  return places.size() > static_cast<std::size_t>(rank) ? swapped_tile_at(was, places[static_cast<std::size_t>(rank)]) : was;
}

const char* to_string(ProbeKind k) {
  switch (k) {
    case ProbeKind::Shift1: return "1-px shifts";
    case ProbeKind::Shift2: return "2-px shifts";
    case ProbeKind::Grown1: return "1-px growth";
    case ProbeKind::Shrunk1: return "1-px shrinkage";
    case ProbeKind::Tile8: return "8x8 tiles";
  }
  return "?";
}

std::size_t densest_change(const Image8& before, const Image8& after, const Image8& decided) {
  std::vector<std::size_t> changed;
  std::vector<std::uint8_t> flagged(before.pixels.size());
  for (std::size_t i = 0; i < before.pixels.size(); ++i)
    if (outputs::is_flag_set(decided.pixels[i]) && before.pixels[i] != after.pixels[i]) changed.push_back(i), flagged[i] = 1;
  return compare::densest_window(flagged, changed, before.width, before.height);
}

bool Probe::shows_something() const {
  return kind == ProbeKind::Tile8 ? densest_changed > compare::kLocalGlitch.densest_fail : wrong > 0;
}

bool ResolvingPower::blind_to(ProbeKind k) const { return std::find(blind.begin(), blind.end(), k) != blind.end(); }
bool ResolvingPower::sees_nothing_of(ProbeKind k) const { return std::find(unseen.begin(), unseen.end(), k) != unseen.end(); }

std::string ResolvingPower::summary() const {
  const auto list = [](const std::vector<std::string>& items) {
    std::string s;
    for (std::size_t i = 0; i < items.size(); ++i) s += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
    return s;
  };
  std::vector<std::string> blind_words, resolved_words, unseen_words;
  for (const ProbeKind k : blind) {
    std::size_t changing = 0, pass = 0;
    for (const Probe& p : probes)
      if (p.kind == k && p.shows_something()) ++changing, pass += p.verdict != compare::Verdict::Fail;
    blind_words.push_back(std::string(to_string(k)) + (changing > 1 ? " (" + std::to_string(pass) + " of " + std::to_string(changing) + " pass)" : ""));
  }
  // Tiles are resolved only where none passes at any place (the sweep in resolving_power()).
  for (const ProbeKind k : resolved)
    resolved_words.push_back(std::string(to_string(k)) + (k == ProbeKind::Tile8 ? " at every place along the boundary" : ""));
  for (const ProbeKind k : unseen)
    if (k != ProbeKind::Tile8) unseen_words.push_back(to_string(k));
  std::string s = blind.empty() ? "" : "blind to " + list(blind_words) + " under this declaration";
  if (!resolved.empty()) s += (s.empty() ? "" : "; ") + std::string("resolves ") + list(resolved_words);
  if (!unseen_words.empty()) s += (s.empty() ? "" : "; ") + std::string("no decided pixel changes under ") + list(unseen_words);
  if (sees_nothing_of(ProbeKind::Tile8))
    s += (s.empty() ? "" : "; ") + std::string("no 8x8 tile changes more than ") + std::to_string(compare::kLocalGlitch.densest_fail) +
         " decided pixels in one 9x9 window";
  return s;
}

ResolvingPower resolving_power(const std::vector<Image8>& masks, const std::vector<Image8>& decided,
                               const compare::Threshold& threshold, const compare::CompareOptions& options) {
  compare::CompareOptions o = options;
  o.visibility.clear();  // the masks alone (resolving_power.hpp)
  o.error_image = false;  // a probe's counts are all it gives
  if (!threshold.bands) o.explain = nullptr;
  const std::size_t lights = masks.size();
  // The displaced-shadow search is the costly part of a comparison and can only raise a verdict to
  // FAIL: a probe that FAILs without it is judged without it, the same verdict at a fraction of the cost.
  compare::CompareOptions quick = o;
  quick.displacement_up_to = -1;
  // Each light's metrics, and the verdict the judge gives them (compare::decide_lights).
  std::vector<std::string> names;
  for (std::size_t i = 0; i < lights; ++i) names.push_back(outputs::mask_name(i, lights));
  struct Judged {
    compare::MaskMetrics total;
    compare::Verdict verdict = compare::Verdict::Pass;
  };
  const auto judged = [&](const ProbeSpec& spec, const std::vector<Image8>& probes, const compare::CompareOptions& with) {
    std::vector<compare::MaskMetrics> each;
    Judged j;
    for (std::size_t i = 0; i < lights; ++i) {
      each.push_back(compare::compare_mask(masks[i], decided[i], probes[i], spec.name, i, with).metrics);
      j.total += each.back();
    }
    j.verdict = compare::decide_lights(each, threshold, names, {}).verdict;
    return j;
  };
  std::vector<std::vector<TilePlace>> places;  // each light's tile places, found once
  for (const Image8& m : masks) places.push_back(tile_places(m, kBusiestTilePlaces));
  ResolvingPower r;
  for (const ProbeSpec& spec : probe_specs()) {
    outputs::throw_if_interrupted();  // SIGINT / SIGTERM: per probe
    std::vector<Image8> probes;
    for (std::size_t i = 0; i < lights; ++i) probes.push_back(probed(masks[i], places[i], spec));
    Judged j = judged(spec, probes, quick);
    if (j.verdict != compare::Verdict::Fail && j.total.unexplained > 0) j = judged(spec, probes, o);
    std::size_t densest = 0;  // a tile's: the local-glitch bound sees a 9 x 9 window (shows_something)
    if (spec.kind == ProbeKind::Tile8)
      for (std::size_t i = 0; i < lights; ++i) densest = std::max(densest, densest_change(masks[i], probes[i], decided[i]));
    r.probes.push_back({spec.kind, spec.name, j.verdict, j.total.wrong, j.total.unexplained, densest});
  }
  // Tiles everywhere else: where the busiest places FAIL, a tile at any other place of the 1-px
  // lattice that shows something and passes makes the case blind to tiles all the same. The sweep
  // (tile_sweep.hpp) screens every place of a light at once; each place it leaves is judged alone,
  // in full, until one passes: that one is listed among the probes, by its place.
  const auto tile_passes = [](const Probe& p) {
    return p.kind == ProbeKind::Tile8 && p.shows_something() && p.verdict != compare::Verdict::Fail;
  };
  for (std::size_t i = 0; i < lights && std::none_of(r.probes.begin(), r.probes.end(), tile_passes); ++i)
    for (const TilePlace& place : tiles_not_failing(masks[i], decided[i], i, threshold, quick)) {
      outputs::throw_if_interrupted();
      std::vector<Image8> probes = masks;
      probes[i] = swapped_tile_at(masks[i], place);
      const ProbeSpec spec{ProbeKind::Tile8, "an 8x8 tile swapped at (" + std::to_string(place.x) + ", " + std::to_string(place.y) + ")" +
                                                 (lights > 1 ? " of light " + std::to_string(i) : "")};
      Judged j = judged(spec, probes, quick);
      if (j.verdict != compare::Verdict::Fail && j.total.unexplained > 0) j = judged(spec, probes, o);
      if (j.verdict == compare::Verdict::Fail) continue;  // the zigzag check or the displaced shadows saw it
      r.probes.push_back({spec.kind, spec.name, j.verdict, j.total.wrong, j.total.unexplained, densest_change(masks[i], probes[i], decided[i])});
      break;
    }
  for (const ProbeKind k : kKinds) {
    bool changes = false, all_fail = true;
    for (const Probe& p : r.probes)
      if (p.kind == k && p.shows_something()) changes = true, all_fail = all_fail && p.verdict == compare::Verdict::Fail;
    (!changes ? r.unseen : all_fail ? r.resolved : r.blind).push_back(k);
  }
  return r;
}

nlohmann::json resolving_power_json(const ResolvingPower& r) {
  nlohmann::json blind = nlohmann::json::array(), unseen = nlohmann::json::array(), probes = nlohmann::json::array();
  for (const ProbeKind k : r.blind) blind.push_back(to_string(k));
  for (const ProbeKind k : r.unseen) unseen.push_back(to_string(k));
  for (const Probe& p : r.probes)
    probes.push_back({{"probe", p.name}, {"verdict", compare::to_string(p.verdict)}, {"wrong", p.wrong}, {"unexplained", p.unexplained}});
  namespace key = record::key;
  return {{key::kSummary, r.summary()}, {key::kBlindTo, blind}, {key::kUnseen, unseen}, {key::kProbes, probes}};
}

}  // namespace shadowref::tolerance
