// compare.cpp — mask comparison on decided pixels, the error image, the verdict (compare.hpp).
#include "shadowref/compare/compare.hpp"

#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/interruption.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <system_error>

namespace shadowref::compare {
namespace {

// A mask value's class (outputs/image.hpp's one reading).
using Class = std::uint8_t;
constexpr Class kShadowed = outputs::kClassShadowed, kNoSurface = outputs::kClassNoSurface, kLit = outputs::kClassLit;
inline Class classify(std::uint8_t v) { return outputs::mask_class(v); }
inline bool exact(std::uint8_t v) { return outputs::is_mask_value(v); }

// A colour as the 4 bytes the row loop stores (the last one overwritten by the next pixel).
constexpr std::array<std::uint8_t, 4> four(const outputs::Rgb& c) { return {c[0], c[1], c[2], 0}; }

// Wrong-pixel codes in the scratch image.
enum Wrong : std::uint8_t { kRight = 0, kFalseShadow = 1, kFalseLight = 2, kCoverage = 3 };

std::string size_text(const Image8& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); }

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g %%", 100.0 * fraction);
  return buf;
}

}  // namespace

double MaskMetrics::wrong_fraction() const {
  if (decided_surface == 0) return wrong == 0 ? 0.0 : 1.0;
  return static_cast<double>(wrong) / static_cast<double>(decided_surface);
}

namespace {
double ratio_to_edges(std::size_t n, std::size_t edges) {
  if (n == 0) return 0.0;
  return static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(edges, 1));
}
}  // namespace

double MaskMetrics::unexplained_ratio() const { return ratio_to_edges(unexplained, edge_pixels); }
double MaskMetrics::explained_ratio() const { return ratio_to_edges(explained_texel + explained_bias, edge_pixels); }

MaskMetrics& MaskMetrics::operator+=(const MaskMetrics& o) {
  width = std::max(width, o.width);
  height = std::max(height, o.height);
  pixels += o.pixels;
  decided += o.decided;
  decided_surface += o.decided_surface;
  wrong += o.wrong;
  false_shadow += o.false_shadow;
  false_light += o.false_light;
  coverage += o.coverage;
  off_values += o.off_values;
  regions += o.regions;
  largest_region = std::max(largest_region, o.largest_region);
  explained_texel += o.explained_texel;
  explained_bias += o.explained_bias;
  unexplained += o.unexplained;
  unexplained_false_light += o.unexplained_false_light;
  unexplained_acne += o.unexplained_acne;
  unexplained_zigzag += o.unexplained_zigzag;
  unexplained_false_light_core += o.unexplained_false_light_core;
  unexplained_core += o.unexplained_core;
  edge_pixels += o.edge_pixels;
  invariant_pixels += o.invariant_pixels;
  displaced += o.displaced;
  densest_unexplained = std::max(densest_unexplained, o.densest_unexplained);
  return *this;
}

std::size_t count_cores(const std::vector<std::uint8_t>& flagged, int w, int h, std::size_t flagged_count) {
  const std::size_t core_area = (2 * kCoreRadius + 1) * (2 * kCoreRadius + 1);
  std::size_t cores = 0;
  for (int y = kCoreRadius; flagged_count >= core_area && y + kCoreRadius < h; ++y)
    for (int x = kCoreRadius; x + kCoreRadius < w; ++x) {
      if (!flagged[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)]) continue;  // most pixels
      bool core = true;
      for (int dy = -kCoreRadius; dy <= kCoreRadius && core; ++dy)
        for (int dx = -kCoreRadius; dx <= kCoreRadius && core; ++dx)
          core = flagged[static_cast<std::size_t>(y + dy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x + dx)] != 0;
      cores += core;
    }
  return cores;
}

namespace {

// A w × h byte image of zeros that costs nothing until written: calloc hands out fresh zero pages
// for large sizes, so that marking a few thousand wrong pixels of a 2048² mask touches a few pages,
// where a std::vector zeroed all 4 MiB first.
struct FreeBytes {
  void operator()(std::uint8_t* p) const { std::free(p); }
};
using ZeroBytes = std::unique_ptr<std::uint8_t[], FreeBytes>;
ZeroBytes zero_bytes(std::size_t n) {
  auto* p = static_cast<std::uint8_t*>(std::calloc(std::max<std::size_t>(n, 1), 1));
  if (!p) throw std::bad_alloc();
  return ZeroBytes(p);
}

// count_cores over the listed flagged pixels only (`flagged` marks exactly those): the same count,
// in time proportional to the list.
std::size_t count_cores_listed(const std::uint8_t* flagged, const std::vector<std::size_t>& list, int w, int h) {
  const std::size_t core_area = (2 * kCoreRadius + 1) * (2 * kCoreRadius + 1);
  if (list.size() < core_area) return 0;
  const std::size_t stride = static_cast<std::size_t>(w);
  std::size_t cores = 0;
  for (const std::size_t i : list) {
    const int x = static_cast<int>(i % stride), y = static_cast<int>(i / stride);
    if (x < kCoreRadius || y < kCoreRadius || x + kCoreRadius >= w || y + kCoreRadius >= h) continue;
    bool core = true;
    for (int dy = -kCoreRadius; dy <= kCoreRadius && core; ++dy)
      for (int dx = -kCoreRadius; dx <= kCoreRadius && core; ++dx)
        core = flagged[static_cast<std::size_t>(y + dy) * stride + static_cast<std::size_t>(x + dx)] != 0;
    cores += core;
  }
  return cores;
}

// The most flagged pixels in the (2 kClusterRadius + 1)² window centred on one of the listed ones
// (`flagged` marks exactly those), clipped to the image: 81 reads per listed pixel.
std::size_t densest_listed(const std::uint8_t* flagged, const std::vector<std::size_t>& list, int w, int h) {
  const std::size_t stride = static_cast<std::size_t>(w);
  std::size_t densest = 0;
  for (const std::size_t i : list) {
    const int x = static_cast<int>(i % stride), y = static_cast<int>(i / stride);
    std::size_t n = 0;
    for (int yy = std::max(0, y - kClusterRadius); yy <= std::min(h - 1, y + kClusterRadius); ++yy)
      for (int xx = std::max(0, x - kClusterRadius); xx <= std::min(w - 1, x + kClusterRadius); ++xx)
        n += flagged[static_cast<std::size_t>(yy) * stride + static_cast<std::size_t>(xx)] != 0;
    densest = std::max(densest, n);
  }
  return densest;
}

}  // namespace

std::size_t densest_window(const std::vector<std::uint8_t>& flagged, const std::vector<std::size_t>& listed, int w, int h) {
  return densest_listed(flagged.data(), listed, w, h);
}

namespace {

// 8-connected regions of the listed wrong pixels (`codes` non-zero exactly there; cleared as the
// fill goes): count and largest, seeds taken in pixel order as regions() does.
void regions_listed(std::uint8_t* codes, const std::vector<std::size_t>& list, int w, int h, MaskMetrics& m) {
  std::vector<std::size_t> stack;
  for (const std::size_t start : list) {
    if (!codes[start]) continue;
    std::size_t size = 0;
    codes[start] = 0;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t p = stack.back();
      stack.pop_back();
      ++size;
      const int x = static_cast<int>(p % static_cast<std::size_t>(w));
      const int y = static_cast<int>(p / static_cast<std::size_t>(w));
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const std::size_t q = static_cast<std::size_t>(ny) * static_cast<std::size_t>(w) + static_cast<std::size_t>(nx);
          if (codes[q]) {
            codes[q] = 0;
            stack.push_back(q);
          }
        }
    }
    ++m.regions;
    m.largest_region = std::max(m.largest_region, size);
  }
}

// The reference's boundary pixels, the scale errors are judged against, are those with a
// 4-neighbour (inside the image) of another class. Boundary pixels of one row of reference classes (`up` and `down`: the rows above and below, the
// row itself at the image's edge), as count_edges: a neighbour outside the image is the pixel itself.
std::size_t row_edges(const std::uint8_t* __restrict up, const std::uint8_t* __restrict row,
                      const std::uint8_t* __restrict down, int w) {
  if (w == 1) return (row[0] != up[0]) | (row[0] != down[0]);
  std::uint32_t edges = (row[0] != row[1]) | (row[0] != up[0]) | (row[0] != down[0]);
  edges += (row[w - 1] != row[w - 2]) | (row[w - 1] != up[w - 1]) | (row[w - 1] != down[w - 1]);
  for (int x = 1; x + 1 < w; ++x)
    edges += static_cast<std::uint32_t>((row[x] != row[x - 1]) | (row[x] != row[x + 1]) | (row[x] != up[x]) |
                                        (row[x] != down[x]));
  return edges;
}

// compare_mask's jobs, in its order: the contract (check_images, refuse_off_values), one pass over
// the rows (scan_rows), the wrong pixels alone (judge_wrong_pixels), their shapes (cores,
// displacement, regions, in compare_mask).

// Three 1-channel images of one size.
void check_images(const Image8& reference, const Image8& decided, const Image8& candidate, const std::string& what) {
  for (const Image8* i : {&reference, &decided, &candidate})
    if (i->channels != 1 || i->pixels.size() != i->pixel_count())
      throw CompareError(CompareError::Kind::BadInput, what + ": images must be 8-bit grey (1 channel)");
  if (decided.width != reference.width || decided.height != reference.height)
    throw CompareError(CompareError::Kind::SizeMismatch, what + ": the reference's decided image is " +
                                                             size_text(decided) + ", its mask " + size_text(reference));
  if (candidate.width != reference.width || candidate.height != reference.height)
    throw CompareError(CompareError::Kind::SizeMismatch, what + ": candidate is " + size_text(candidate) +
                                                             ", reference is " + size_text(reference));
}

// The contract allows three values and nothing is rounded: a mask written as 10 / 250 is a broken
// writer, not a near miss (docs/output-contract.md). Refused before anything is judged (the cause
// model is the costly part), naming the count and the first such pixel. Cost: one pass, vectorised.
void refuse_off_values(const Image8& candidate, const std::string& what) {
  const std::uint8_t* __restrict cand = candidate.pixels.data();
  const std::size_t n = candidate.pixel_count();
  std::size_t off = 0;
  for (std::size_t i = 0; i < n; ++i) off += !exact(cand[i]);
  if (off == 0) return;
  std::size_t first = 0;
  while (exact(cand[first])) ++first;
  const std::size_t w = static_cast<std::size_t>(candidate.width);
  throw CompareError(CompareError::Kind::BadInput,
                     what + ": " + std::to_string(off) + " pixel(s) hold values other than 255 (lit), 0 (shadowed) "
                     "and 128 (no surface), e.g. " + std::to_string(cand[first]) + " at (" + std::to_string(first % w) + ", " +
                         std::to_string(first / w) + ")");
}

// One pass over the rows, vectorised: the reference's classes (three rows kept for its edges), the
// decided and invariant counts, each pixel's background in the error image (the dimmed reference,
// or the undecided colour), and the wrong pixels, returned as a list (they are few, or the verdict
// is a FAIL anyway).
std::vector<std::size_t> scan_rows(const Image8& reference, const Image8& decided, const Image8& candidate, bool invariant_on,
                                   MaskComparison& out) {
  const int w = reference.width, h = reference.height;
  MaskMetrics& m = out.metrics;
  const std::uint8_t* ref = reference.pixels.data();
  const std::uint8_t* dec = decided.pixels.data();
  const std::uint8_t* cand = candidate.pixels.data();
  std::uint8_t* err = out.error.pixels.empty() ? nullptr : out.error.pixels.data();  // null: no error image painted
  // The dimmed reference under the error colours, by class (shadowed, no surface, lit), and the
  // undecided colour: each as 4 bytes, so that a pixel's colour is one 4-byte store whose last byte
  // the next pixel overwrites.
  static constexpr std::array<std::uint8_t, 4> kColour[4] = {four(outputs::kDimmedShadowed), four(outputs::kDimmedNoSurface),
                                                             four(outputs::kDimmedLit), four(error_colour(ErrorClass::Undecided))};
  static_assert(kShadowed == 0 && kNoSurface == 1 && kLit == 2);
  const std::size_t stride = static_cast<std::size_t>(w);
  const std::uint8_t invariant = invariant_on ? 1 : 0;
  std::vector<std::uint8_t> cls_rows(3 * stride), colour(stride), wrong_row(stride);
  std::uint8_t* rows[3] = {cls_rows.data(), cls_rows.data() + stride, cls_rows.data() + 2 * stride};
  const auto classify_row = [&](int y, std::uint8_t* __restrict out_row) {
    const std::uint8_t* __restrict in = ref + static_cast<std::size_t>(y) * stride;
    for (int x = 0; x < w; ++x) out_row[x] = classify(in[x]);
  };
  classify_row(0, rows[1]);
  std::vector<std::size_t> wrong;
  std::size_t edges = 0, decided_count = 0, decided_surface = 0, invariant_pixels = 0;
  for (int y = 0; y < h; ++y) {
    // rows[0] above, rows[1] this row, rows[2] below (the row itself at the image's edges).
    if (y + 1 < h) classify_row(y + 1, rows[2]);
    const std::uint8_t* up = y > 0 ? rows[0] : rows[1];
    const std::uint8_t* down = y + 1 < h ? rows[2] : rows[1];
    edges += row_edges(up, rows[1], down, w);
    const std::size_t first = static_cast<std::size_t>(y) * stride;
    const std::uint8_t* __restrict rc = rows[1];
    const std::uint8_t* __restrict cv = cand + first;
    const std::uint8_t* __restrict dv = dec + first;
    std::uint8_t* __restrict col = colour.data();
    std::uint8_t* __restrict wr = wrong_row.data();
    std::uint32_t row_decided = 0, row_surface = 0, row_invariant = 0, row_wrong = 0;
    for (int x = 0; x < w; ++x) {
      const std::uint8_t r = rc[x], c = classify(cv[x]);
      const std::uint8_t d = outputs::flag_bit(dv[x]);
      // Judged although undecided: the scene's invariant (no cast shadow) and a false shadow.
      const std::uint8_t inv = static_cast<std::uint8_t>((d ^ 1) & invariant & (r == kLit) & (c == kShadowed));
      const std::uint8_t judged = d | inv;
      row_decided += d;
      row_surface += d & (r != kNoSurface);
      row_invariant += inv;
      col[x] = judged ? r : std::uint8_t{3};
      wr[x] = judged & (r != c);
      row_wrong += wr[x];
    }
    decided_count += row_decided;
    decided_surface += row_surface;
    invariant_pixels += row_invariant;
    if (err) {
      std::uint8_t* e = err + 3 * first;
      for (int x = 0; x + 1 < w || (x + 1 == w && y + 1 < h); ++x) std::memcpy(e + 3 * x, kColour[col[x]].data(), 4);
      if (y + 1 == h) std::memcpy(e + 3 * static_cast<std::size_t>(w - 1), kColour[col[w - 1]].data(), 3);  // the image's last pixel
    }
    if (row_wrong)
      for (int x = 0; x < w; ++x)
        if (wr[x]) wrong.push_back(first + static_cast<std::size_t>(x));
    std::rotate(rows, rows + 1, rows + 3);
  }
  m.edge_pixels = edges;
  m.decided = decided_count;
  m.decided_surface = decided_surface;
  m.invariant_pixels = invariant_pixels;
  return wrong;
}

// What judge_wrong_pixels leaves for the shapes: each wrong pixel's kind (codes) and the unexplained
// ones, flagged and listed.
struct WrongPixels {
  ZeroBytes codes, flagged;
  std::vector<std::size_t> unexplained, unexplained_false_light;
};

// The wrong pixels alone: their kind, their cause (asked of options.explain for shadow errors), their
// count by kind and cause, and their colour in the error image (outputs::kErrorClasses).
WrongPixels judge_wrong_pixels(const Image8& reference, const Image8& candidate, const std::vector<std::size_t>& wrong,
                               std::size_t light, const CompareOptions& options, MaskComparison& out) {
  MaskMetrics& m = out.metrics;
  const std::size_t n = reference.pixel_count(), stride = static_cast<std::size_t>(reference.width);
  const std::uint8_t* ref = reference.pixels.data();
  const std::uint8_t* cand = candidate.pixels.data();
  std::uint8_t* err = out.error.pixels.empty() ? nullptr : out.error.pixels.data();  // null: no error image painted
  WrongPixels wp;
  wp.codes = wrong.empty() ? nullptr : zero_bytes(n);
  wp.flagged = wrong.empty() ? nullptr : zero_bytes(n);
  // The pixels no correct render gives together, marked in `codes` until each is judged below.
  constexpr std::uint8_t kImpossible = 0x80;
  if (options.impossible && !wrong.empty())
    for (const std::size_t i : (*options.impossible)(light, reference, candidate, wrong)) wp.codes[i] = kImpossible;
  for (const std::size_t i : wrong) {
    if (((&i - wrong.data()) & 1023) == 0) outputs::throw_if_interrupted();  // SIGINT / SIGTERM: per 1024 causes asked
    const Class r = classify(ref[i]), c = classify(cand[i]);
    const int x = static_cast<int>(i % stride), y = static_cast<int>(i / stride);
    std::uint8_t code;
    const outputs::Rgb* paint;
    if (r == kNoSurface || c == kNoSurface) {
      code = kCoverage;
      ++m.coverage;
      paint = &error_colour(ErrorClass::Coverage);
    } else if (r == kLit) {
      code = kFalseShadow;
      ++m.false_shadow;
      paint = &error_colour(ErrorClass::FalseShadow);
    } else {
      code = kFalseLight;
      ++m.false_light;
      paint = &error_colour(ErrorClass::FalseLight);
    }
    const bool impossible = wp.codes[i] == kImpossible;
    wp.codes[i] = code;
    ++m.wrong;
    // A cause for a shadow error (coverage has none), unless it is one of the impossible ones.
    Cause cause = Cause::Unexplained;
    if (impossible && code != kCoverage)
      ++m.unexplained_zigzag;
    else if (code != kCoverage && options.explain)
      cause = (*options.explain)(light, x, y, c == kLit);
    if (cause == Cause::TexelFootprint) {
      ++m.explained_texel;
      paint = &error_colour(ErrorClass::Texel);
    } else if (cause == Cause::DepthBias) {
      ++m.explained_bias;
      paint = &error_colour(ErrorClass::Bias);
    } else {
      ++m.unexplained;
      if (code == kFalseLight) {
        ++m.unexplained_false_light;
        wp.unexplained_false_light.push_back(i);
      }
      if (cause == Cause::Acne) {
        ++m.unexplained_acne;
        paint = &error_colour(ErrorClass::Acne);
      }
      wp.flagged[i] = 1;
      wp.unexplained.push_back(i);
    }
    if (err) std::memcpy(err + 3 * i, paint->data(), 3);
  }
  return wp;
}

}  // namespace

MaskComparison compare_mask(const Image8& reference, const Image8& decided, const Image8& candidate,
                            const std::string& what, std::size_t light, const CompareOptions& options) {
  check_images(reference, decided, candidate, what);
  refuse_off_values(candidate, what);
  const int w = reference.width, h = reference.height;
  const std::size_t n = reference.pixel_count();
  MaskComparison out;
  MaskMetrics& m = out.metrics;
  m.width = w;
  m.height = h;
  m.pixels = n;
  if (options.error_image) out.error = Image8{w, h, 3, std::vector<std::uint8_t>(3 * n)};
  const std::vector<std::size_t> wrong = scan_rows(reference, decided, candidate, options.no_cast_shadow_invariant, out);
  WrongPixels wp = judge_wrong_pixels(reference, candidate, wrong, light, options, out);
  if (options.list_unexplained) out.unexplained = wp.unexplained;
  // The shapes of the unexplained pixels: cores, a displacement that makes them right, regions.
  if (!wrong.empty()) {
    m.unexplained_core = count_cores_listed(wp.flagged.get(), wp.unexplained, w, h);
    m.densest_unexplained = densest_listed(wp.flagged.get(), wp.unexplained, w, h);
    // The same over the false light alone (an expected failure's predicted kind, conform.cpp).
    for (const std::size_t i : wp.unexplained) wp.flagged[i] = wp.codes[i] == kFalseLight;
    m.unexplained_false_light_core = count_cores_listed(wp.flagged.get(), wp.unexplained_false_light, w, h);
  }
  if (!wp.unexplained.empty() &&
      static_cast<double>(wp.unexplained.size()) <= options.displacement_up_to * static_cast<double>(m.edge_pixels)) {
    std::vector<std::size_t> unexplained_shadow;  // coverage has its own count
    for (const std::size_t i : wp.unexplained)
      if (wp.codes[i] != kCoverage) unexplained_shadow.push_back(i);
    out.displacement = find_displacement(reference, decided, candidate, options.no_cast_shadow_invariant, unexplained_shadow,
                                         m.false_shadow + m.false_light);
    m.displaced = out.displacement.fixed_unexplained;
  }
  if (m.wrong) regions_listed(wp.codes.get(), wrong, w, h, m);
  return out;
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::Pass: return "pass";
    case Verdict::QualityWarning: return "warning";
    case Verdict::Fail: return "fail";
  }
  return "?";
}

Decision decide(const MaskMetrics& m, const Threshold& t, const std::string& displaced_how) {
  Decision j;
  const auto raise = [&](Verdict v, std::string why) {
    j.verdict = std::max(j.verdict, v);
    j.reasons.push_back(std::move(why));
  };
  const std::string edges = std::to_string(m.edge_pixels) + " edge pixels";
  if (m.unexplained_core > 0)
    raise(Verdict::Fail, std::to_string(m.unexplained_core) + " unexplained core pixel(s): a wrong region with a thick core, "
                         "not a boundary band (" + std::string(t.name) + ")");
  if (m.unexplained_ratio() > t.unexplained_fail)
    raise(Verdict::Fail, "unexplained wrong " + std::to_string(m.unexplained) + " px = " + percent(m.unexplained_ratio()) +
                             " of " + edges + " > " + percent(t.unexplained_fail) + " (fail bound, " + std::string(t.name) + ")");
  if (static_cast<double>(m.displaced) > kDisplaced.displaced_fail * static_cast<double>(std::max<std::size_t>(m.edge_pixels, 1)))
    raise(Verdict::Fail, std::to_string(m.displaced) + " unexplained px = " +
                             percent(ratio_to_edges(m.displaced, m.edge_pixels)) + " of " + edges +
                             " come right when the shadows are moved back" + (displaced_how.empty() ? "" : " (" + displaced_how + ")") +
                             ": displaced shadows > " + percent(kDisplaced.displaced_fail) + " (fail bound)");
  if (t.bands && m.densest_unexplained > kLocalGlitch.densest_fail)
    raise(Verdict::Fail, std::to_string(m.densest_unexplained) + " unexplained px in one 9 x 9 window: a local glitch > " +
                             std::to_string(kLocalGlitch.densest_fail) + " (fail bound)");
  if (m.explained_ratio() > t.explained_warn)
    raise(Verdict::QualityWarning, "explained wrong " + std::to_string(m.explained_texel + m.explained_bias) + " px = " +
                                       percent(m.explained_ratio()) + " of " + edges + " > " + percent(t.explained_warn) +
                                       " (quality bound, " + std::string(t.name) + ")");
  return j;
}

Decision decide_lights(const std::vector<MaskMetrics>& lights, const Threshold& threshold,
                       const std::vector<std::string>& names, const std::vector<std::string>& displaced_how) {
  if (lights.size() == 1) return decide(lights[0], threshold, displaced_how.empty() ? std::string() : displaced_how[0]);
  Decision out;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    Decision d = decide(lights[i], threshold, i < displaced_how.size() ? displaced_how[i] : std::string());
    out.verdict = std::max(out.verdict, d.verdict);
    for (std::string& reason : d.reasons) out.reasons.push_back((i < names.size() ? names[i] : "light " + std::to_string(i)) + ": " + reason);
  }
  return out;
}

FolderImages read_folder_images(const std::filesystem::path& reference_dir, const std::filesystem::path& candidate_dir) {
  FolderImages out;
  out.masks = outputs::find_mask_names(reference_dir);
  std::error_code ec;
  if (!std::filesystem::is_directory(candidate_dir, ec))
    throw CompareError(CompareError::Kind::BadInput, candidate_dir.string() + ": not a folder");
  // A mask for a light the reference does not have (mask_<n>.png, mask.png beside per-light masks,
  // mask_0.png for a one-light scene) is a producer that counted the lights wrongly, not a detail:
  // refused before any image is read.
  const std::size_t n = out.masks.size();
  for (const std::string& stray : {outputs::mask_name(n, n + 1), n == 1 ? outputs::mask_name(0, 2) : outputs::mask_name(0, 1)})
    if (std::filesystem::exists(candidate_dir / stray, ec) || std::filesystem::is_symlink(candidate_dir / stray, ec))
      throw CompareError(CompareError::Kind::BadInput,
                         (candidate_dir / stray).string() + ": the reference has " + std::to_string(n) + " light(s), masks " +
                             (n == 1 ? out.masks[0] : out.masks.front() + " ... " + out.masks.back()));
  for (std::size_t i = 0; i < out.masks.size(); ++i) {
    const std::string& name = out.masks[i];
    if (!std::filesystem::exists(candidate_dir / name, ec))
      throw CompareError(CompareError::Kind::BadInput,
                         (candidate_dir / name).string() + ": no such file (the reference has " +
                             std::to_string(out.masks.size()) + " light mask(s): " +
                             (out.masks.size() == 1 ? out.masks[0] : out.masks.front() + " ... " + out.masks.back()) + ")");
    out.reference.push_back(read_image8(reference_dir / name, 1));
    out.decided.push_back(read_image8(reference_dir / outputs::decided_name(i, out.masks.size()), 1));
    out.candidate.push_back(read_image8(candidate_dir / name, 1, out.reference.back().width, out.reference.back().height));
    out.candidate_files.push_back((candidate_dir / name).string());
  }
  out.fractions.resize(out.masks.size());
  return out;
}

void add_fractions(FolderImages& images, const std::filesystem::path& reference_dir, const std::filesystem::path& candidate_dir,
                   const CompareOptions& options) {
  std::error_code ec;
  for (std::size_t i = 0; i < images.masks.size(); ++i) {
    if (!(i < options.visibility.size() && options.visibility[i].tolerance >= 0)) continue;
    const int w = images.reference[i].width, h = images.reference[i].height;
    const std::string vis = outputs::visibility_name(i, images.masks.size());
    if (!std::filesystem::exists(candidate_dir / vis, ec))
      throw CompareError(CompareError::Kind::BadInput, (candidate_dir / vis).string() +
                                                           ": no such file (a soft technique's lit fraction, 8-bit grey, "
                                                           "beside its mask)");
    if (images.covered.pixels.empty()) images.covered = read_image8(reference_dir / outputs::kCoveredName, 1, w, h);
    FolderImages::Fraction f;
    f.reference = outputs::read_exr(reference_dir / outputs::per_light_name("visibility", "exr", i, images.masks.size()), w, h);
    f.candidate = read_image8(candidate_dir / vis, 1, w, h);
    images.fractions[i] = std::move(f);
  }
}

FolderComparison compare_images(const FolderImages& images, const Threshold& threshold, const CompareOptions& options) {
  FolderComparison out;
  out.threshold = &threshold;
  out.masks = images.masks;
  CompareOptions o = options;
  if (!threshold.bands) o.explain = nullptr;  // exact techniques: no texel or bias band
  for (std::size_t i = 0; i < images.masks.size(); ++i) {
    out.per_light.push_back(compare_mask(images.reference[i], images.decided[i], images.candidate[i], images.candidate_files[i], i, o));
    out.total += out.per_light.back().metrics;
    // Soft shadows: the lit fraction of a light with an area.
    out.visibility.emplace_back();
    if (i >= images.fractions.size() || !images.fractions[i]) continue;
    out.visibility.back() = compare_visibility(images.fractions[i]->reference, images.covered, images.fractions[i]->candidate,
                                               images.candidate[i], options.visibility[i], options.explain_visibility, i,
                                               options.visibility_texel_shift);
    if (!out.visibility_total) out.visibility_total = VisibilityMetrics{};
    *out.visibility_total += out.visibility.back()->metrics;
  }
  // Each light decided alone (decide_lights), with its move where one was found.
  std::vector<MaskMetrics> lights;
  std::vector<std::string> displaced_how;
  for (const MaskComparison& c : out.per_light) {
    lights.push_back(c.metrics);
    displaced_how.push_back(c.displacement.fixed_unexplained == 0 ? std::string() : describe(c.displacement.move));
  }
  out.decision = decide_lights(lights, threshold, out.masks, displaced_how);
  if (out.visibility_total) decide_visibility(*out.visibility_total, out.decision);
  return out;
}

FolderComparison compare_folders(const std::filesystem::path& reference_dir,
                                 const std::filesystem::path& candidate_dir, const Threshold& threshold,
                                 const CompareOptions& options) {
  FolderImages images = read_folder_images(reference_dir, candidate_dir);
  add_fractions(images, reference_dir, candidate_dir, options);
  return compare_images(images, threshold, options);
}

void decide_visibility(const VisibilityMetrics& m, Decision& j) {
  char buf[320];
  const auto fail = [&](const std::string& reason) {
    j.verdict = Verdict::Fail;
    j.reasons.push_back(reason);
  };
  if (m.unexplained_core > 0) {
    std::snprintf(buf, sizeof buf, "visibility: %zu unexplained core pixel(s) (a 5x5 block off by more than sampling)",
                  m.unexplained_core);
    fail(buf);
  }
  if (m.unexplained_ratio() > kPenumbra.unexplained_fail) {
    std::snprintf(buf, sizeof buf, "visibility: %.2f %% of the penumbra unexplained (bound %.2f %%)",
                  100.0 * m.unexplained_ratio(), 100.0 * kPenumbra.unexplained_fail);
    fail(buf);
  }
  // What the map's texels alone may leave, said where it was asked for (visibility.hpp).
  const auto with_texels = [&m](double fail_bound) {
    char s[96] = "";
    if (m.sum_penumbra_texel_error > 0)
      std::snprintf(s, sizeof s, "; with the map's texel error %.3f: %.3f", m.mean_penumbra_texel_error(), fail_bound);
    return std::string(s);
  };
  if (m.local_mean_error_bound == 0) {  // a grid: its plain mean judges the width
    if (m.mean_penumbra_error() > m.mean_error_fail()) {
      std::snprintf(buf, sizeof buf,
                    "visibility: mean error over the penumbra %.3f (bound %.3f, what sampling alone leaves%s)",
                    m.mean_penumbra_error(), m.mean_error_bound, with_texels(m.mean_error_fail()).c_str());
      fail(buf);
    }
    return;
  }
  // Random taps: the width on the local means, the rest is the estimator's noise (visibility.hpp).
  if (m.mean_penumbra_local_error() > m.local_mean_error_fail()) {
    std::snprintf(buf, sizeof buf,
                  "visibility: mean error of the 3x3 local means over the penumbra %.3f (bound %.3f, what random taps "
                  "leave%s): a penumbra of the wrong width",
                  m.mean_penumbra_local_error(), m.local_mean_error_bound, with_texels(m.local_mean_error_fail()).c_str());
    fail(buf);
  } else if (m.mean_penumbra_error() > m.mean_error_fail()) {
    std::snprintf(buf, sizeof buf,
                  "visibility: noise: mean error over the penumbra %.3f beyond the declared taps' spread (bound %.3f%s); "
                  "its local means are right (%.3f)",
                  m.mean_penumbra_error(), m.mean_error_bound, with_texels(m.mean_error_fail()).c_str(),
                  m.mean_penumbra_local_error());
    if (j.verdict != Verdict::Fail) j.verdict = Verdict::QualityWarning;
    j.reasons.push_back(buf);
  }
}

std::vector<std::string> write_error_images(const FolderComparison& c, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < c.per_light.size(); ++i) {
    const std::string name = outputs::per_light_name("error", "png", i, c.per_light.size());
    outputs::write_png(c.per_light[i].error, dir / name);
    names.push_back(name);
  }
  for (std::size_t i = 0; i < c.visibility.size(); ++i) {
    if (!c.visibility[i]) continue;
    const std::string name = outputs::per_light_name("visibility_error", "png", i, c.visibility.size());
    outputs::write_png(c.visibility[i]->error, dir / name);
    names.push_back(name);
  }
  return names;
}

}  // namespace shadowref::compare
