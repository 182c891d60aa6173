// resolving_power.cpp — the probes of resolving_power.hpp: the reference's own masks with one
// blatant error each, judged as the candidate was.
#include "shadowref/conform/resolving_power.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <utility>
#include <vector>

#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/interruption.hpp"

namespace shadowref::conform {
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
  for (const auto& [rank, where] : {std::pair{0, "busiest"}, {1, "second busiest"}, {2, "third busiest"}})
    out.push_back({ProbeKind::Tile8, std::string("an 8x8 tile swapped at the ") + where + " place", 0, 0, rank});
  return out;
}

Image8 probed(const Image8& mask, const ProbeSpec& p) {
  switch (p.kind) {
    case ProbeKind::Shift1:
    case ProbeKind::Shift2: return shifted(mask, p.dx, p.dy);
    case ProbeKind::Grown1: return morphed(mask, true);
    case ProbeKind::Shrunk1: return morphed(mask, false);
    case ProbeKind::Tile8: return swapped_tile(mask, p.rank);
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

Image8 swapped_tile(const Image8& was, int rank) {
  Image8 m = was;
  std::vector<std::pair<int, int>> taken;
  int bx = 0, by = 0, best = -1;
  for (int r = 0; r <= rank; ++r) {
    best = -1;
    for (int y = 0; y + 8 <= m.height; y += 4)
      for (int x = 0; x + 16 <= m.width; x += 4) {
        bool near = false;
        for (const auto& [tx, ty] : taken) near = near || (std::abs(x - tx) < 16 && std::abs(y - ty) < 16);
        if (near) continue;
        int differ = 0;
        for (int v = 0; v < 8; ++v)
          for (int u = 0; u < 8; ++u) differ += at(was, x + u, y + v) != at(was, x + u + 8, y + v);
        if (differ > best) best = differ, bx = x, by = y;
      }
    if (best < 0) return m;  // no place left
    taken.emplace_back(bx, by);
  }
  for (int v = 0; v < 8; ++v)
    for (int u = 0; u < 8; ++u) std::swap(at(m, bx + u, by + v), at(m, bx + u + 8, by + v));
  return m;
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

bool Probe::shows_something() const {
  return kind == ProbeKind::Tile8 ? wrong > compare::kLocalGlitch.densest_fail : wrong > 0;
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
  // A tile probe speaks for the places it was put (the three busiest 8 x 8 windows of the boundary),
  // not for the whole boundary: a tile swapped elsewhere may pass where these FAIL.
  for (const ProbeKind k : resolved)
    resolved_words.push_back(std::string(to_string(k)) + (k == ProbeKind::Tile8 ? " at the three busiest places probed" : ""));
  for (const ProbeKind k : unseen)
    if (k != ProbeKind::Tile8) unseen_words.push_back(to_string(k));
  std::string s = blind.empty() ? "" : "blind to " + list(blind_words) + " under this declaration";
  if (!resolved.empty()) s += (s.empty() ? "" : "; ") + std::string("resolves ") + list(resolved_words);
  if (!unseen_words.empty()) s += (s.empty() ? "" : "; ") + std::string("no decided pixel changes under ") + list(unseen_words);
  if (sees_nothing_of(ProbeKind::Tile8))
    s += (s.empty() ? "" : "; ") + std::string("no 8x8 tile changes more than ") + std::to_string(compare::kLocalGlitch.densest_fail) +
         " decided pixels";
  return s;
}

ResolvingPower resolving_power(const std::filesystem::path& reference_dir, std::size_t lights,
                               const compare::Threshold& threshold, const compare::CompareOptions& options) {
  compare::CompareOptions o = options;
  o.visibility.clear();  // the masks alone (resolving_power.hpp)
  o.error_image = false;  // a probe's counts are all it gives
  if (!threshold.bands) o.explain = nullptr;
  std::vector<Image8> masks, decided;
  for (std::size_t i = 0; i < lights; ++i) {
    masks.push_back(outputs::read_image8(reference_dir / outputs::mask_name(i, lights), 1));
    decided.push_back(outputs::read_image8(reference_dir / outputs::decided_name(i, lights), 1, masks.back().width,
                                           masks.back().height));
  }
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
  ResolvingPower r;
  for (const ProbeSpec& spec : probe_specs()) {
    outputs::throw_if_interrupted();  // SIGINT / SIGTERM: per probe
    std::vector<Image8> probes;
    for (std::size_t i = 0; i < lights; ++i) probes.push_back(probed(masks[i], spec));
    Judged j = judged(spec, probes, quick);
    if (j.verdict != compare::Verdict::Fail && j.total.unexplained > 0) j = judged(spec, probes, o);
    r.probes.push_back({spec.kind, spec.name, j.verdict, j.total.wrong, j.total.unexplained});
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
  return {{"summary", r.summary()}, {"blind_to", blind}, {"unseen", unseen}, {"probes", probes}};
}

}  // namespace shadowref::conform
