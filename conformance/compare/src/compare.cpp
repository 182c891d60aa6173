// compare.cpp — mask comparison on decided pixels, the error image, the verdict (compare.hpp).
#include "shadowref/compare/compare.hpp"

#include "shadowref/outputs/file_names.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <system_error>

namespace shadowref::compare {
namespace {

enum Class : std::uint8_t { kShadowed = 0, kNoSurface = 1, kLit = 2 };

// Nearest of 0 / 128 / 255: 0, 1 or 2 thresholds passed (branchless, so that loops over it vectorise).
inline Class classify(std::uint8_t v) { return static_cast<Class>((v >= 64) + (v >= 192)); }
inline bool exact(std::uint8_t v) { return outputs::is_mask_value(v); }

// The reference's boundary pixels, the scale errors are judged against: those with a 4-neighbour
// (inside the image) of another class. Branchless over whole rows, so that it vectorises: a
// neighbour outside the image is replaced by the pixel itself, which never differs.
std::size_t count_edges(const std::uint8_t* ref, int w, int h) {
  std::size_t edges = 0;
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* row = ref + static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
    const std::uint8_t* up = y > 0 ? row - w : row;
    const std::uint8_t* down = y + 1 < h ? row + w : row;
    for (int x = 0; x < w; ++x) {
      const Class c = classify(row[x]);
      const Class l = classify(row[x > 0 ? x - 1 : x]), r = classify(row[x + 1 < w ? x + 1 : x]);
      edges += (c != l) | (c != r) | (c != classify(up[x])) | (c != classify(down[x]));
    }
  }
  return edges;
}

// Wrong-pixel codes in the scratch image.
enum Wrong : std::uint8_t { kRight = 0, kFalseShadow = 1, kFalseLight = 2, kCoverage = 3 };

std::string size_text(const Image8& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); }

// 8-connected regions of non-zero codes: count and largest, by an explicit-stack flood fill that
// visits wrong pixels only (clears `codes` as it goes).
void regions(std::vector<std::uint8_t>& codes, int w, int h, MaskMetrics& m) {
  std::vector<std::size_t> stack;
  const std::size_t n = codes.size();
  for (std::size_t start = 0; start < n; ++start) {
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
  unexplained_false_light_core += o.unexplained_false_light_core;
  unexplained_core += o.unexplained_core;
  edge_pixels += o.edge_pixels;
  invariant_pixels += o.invariant_pixels;
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

MaskComparison compare_mask(const Image8& reference, const Image8& decided, const Image8& candidate,
                            const std::string& what, std::size_t light, const CompareOptions& options) {
  for (const Image8* i : {&reference, &decided, &candidate})
    if (i->channels != 1 || i->pixels.size() != i->pixel_count())
      throw CompareError(CompareError::Kind::BadInput, what + ": images must be 8-bit grey (1 channel)");
  if (decided.width != reference.width || decided.height != reference.height)
    throw CompareError(CompareError::Kind::SizeMismatch, what + ": the reference's decided image is " +
                                                             size_text(decided) + ", its mask " + size_text(reference));
  if (candidate.width != reference.width || candidate.height != reference.height)
    throw CompareError(CompareError::Kind::SizeMismatch, what + ": candidate is " + size_text(candidate) +
                                                             ", reference is " + size_text(reference));
  const int w = reference.width, h = reference.height;
  const std::size_t n = reference.pixel_count();
  MaskComparison out;
  MaskMetrics& m = out.metrics;
  m.width = w;
  m.height = h;
  m.pixels = n;
  out.error = Image8{w, h, 3, std::vector<std::uint8_t>(3 * n)};
  std::vector<std::uint8_t> codes(n, kRight);
  std::vector<std::uint8_t> unexplained(n, 0);
  const std::uint8_t* ref = reference.pixels.data();
  const std::uint8_t* dec = decided.pixels.data();
  const std::uint8_t* cand = candidate.pixels.data();
  std::uint8_t* err = out.error.pixels.data();
  // The dimmed reference under the error colours: lit, shadowed, no surface.
  static constexpr std::uint8_t kDim[3][3] = {{55, 55, 55}, {28, 28, 42}, {150, 150, 150}};
  // Rows and columns are walked as such: a division per pixel cost more than the rest of the loop.
  const std::size_t stride = static_cast<std::size_t>(w);
  m.edge_pixels = count_edges(ref, w, h);
  // The per-pixel counts live in locals: the loop writes through std::uint8_t pointers, which may
  // alias anything, so counters in `m` were loaded and stored back at every pixel (2.5 times slower).
  std::size_t off_values = 0, decided_count = 0, decided_surface = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
    const std::size_t i = static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x);
    const Class r = classify(ref[i]);
    const Class c = classify(cand[i]);
    off_values += !exact(cand[i]);
    const std::uint8_t* colour = kDim[r];
    const bool judged_by_invariant =
        dec[i] < 128 && options.no_cast_shadow_invariant && r == kLit && c == kShadowed;
    if (dec[i] >= 128 || judged_by_invariant) {
      if (dec[i] >= 128) {
        ++decided_count;
        decided_surface += r != kNoSurface;
      } else {
        ++m.invariant_pixels;
      }
      if (r != c) {
        std::uint8_t code;
        if (r == kNoSurface || c == kNoSurface) {
          code = kCoverage;
          ++m.coverage;
          colour = kErrorColours.coverage;
        } else if (r == kLit) {
          code = kFalseShadow;
          ++m.false_shadow;
          colour = kErrorColours.false_shadow;
        } else {
          code = kFalseLight;
          ++m.false_light;
          colour = kErrorColours.false_light;
        }
        codes[i] = code;
        ++m.wrong;
        // A cause for a shadow error (coverage has none).
        Cause cause = Cause::Unexplained;
        if (code != kCoverage && options.explain) cause = (*options.explain)(light, x, y, c == kLit);
        if (cause == Cause::TexelFootprint) {
          ++m.explained_texel;
          colour = kErrorColours.texel;
        } else if (cause == Cause::DepthBias) {
          ++m.explained_bias;
          colour = kErrorColours.bias;
        } else {
          ++m.unexplained;
          if (code == kFalseLight) ++m.unexplained_false_light;
          if (cause == Cause::Acne) {
            ++m.unexplained_acne;
            colour = kErrorColours.acne;
          }
          unexplained[i] = 1;
        }
      }
    } else {
      colour = kErrorColours.undecided;
    }
    err[3 * i + 0] = colour[0];
    err[3 * i + 1] = colour[1];
    err[3 * i + 2] = colour[2];
  }
  m.off_values = off_values;
  m.decided = decided_count;
  m.decided_surface = decided_surface;
  m.unexplained_core = count_cores(unexplained, w, h, m.unexplained);
  // The same over the false light alone (an expected failure's predicted kind, conform.cpp).
  for (std::size_t i = 0; i < n; ++i) unexplained[i] = unexplained[i] && codes[i] == kFalseLight;
  m.unexplained_false_light_core = count_cores(unexplained, w, h, m.unexplained_false_light);
  if (m.off_values) {
    // The contract allows three values and nothing is rounded: a mask written as 10 / 250 is a
    // broken writer, not a near miss (docs/output-contract.md).
    std::size_t first = 0;
    while (exact(cand[first])) ++first;
    throw CompareError(CompareError::Kind::BadInput,
                       what + ": " + std::to_string(m.off_values) + " pixel(s) hold values other than 255 (lit), 0 (shadowed) "
                       "and 128 (no surface), e.g. " + std::to_string(cand[first]) + " at (" +
                       std::to_string(first % static_cast<std::size_t>(w)) + ", " + std::to_string(first / static_cast<std::size_t>(w)) + ")");
  }
  if (m.wrong) regions(codes, w, h, m);
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

Judgement judge(const MaskMetrics& m, const Threshold& t) {
  Judgement j;
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
  if (m.explained_ratio() > t.explained_warn)
    raise(Verdict::QualityWarning, "explained wrong " + std::to_string(m.explained_texel + m.explained_bias) + " px = " +
                                       percent(m.explained_ratio()) + " of " + edges + " > " + percent(t.explained_warn) +
                                       " (quality bound, " + std::string(t.name) + ")");
  return j;
}

FolderComparison compare_folders(const std::filesystem::path& reference_dir,
                                 const std::filesystem::path& candidate_dir, const Threshold& threshold,
                                 const CompareOptions& options) {
  FolderComparison out;
  out.threshold = &threshold;
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
    const std::string decided_name = outputs::decided_name(i, out.masks.size());
    if (!std::filesystem::exists(candidate_dir / name, ec))
      throw CompareError(CompareError::Kind::BadInput,
                         (candidate_dir / name).string() + ": no such file (the reference has " +
                             std::to_string(out.masks.size()) + " light mask(s): " +
                             (out.masks.size() == 1 ? out.masks[0] : out.masks.front() + " ... " + out.masks.back()) + ")");
    const Image8 ref = read_image8(reference_dir / name, 1);
    const Image8 dec = read_image8(reference_dir / decided_name, 1);
    const Image8 cand = read_image8(candidate_dir / name, 1, ref.width, ref.height);
    CompareOptions o = options;
    if (!threshold.bands) o.explain = nullptr;  // exact techniques: no texel or bias band
    out.per_light.push_back(compare_mask(ref, dec, cand, (candidate_dir / name).string(), i, o));
    out.total += out.per_light.back().metrics;
    // Soft shadows: the lit fraction of a light with an area.
    const bool soft = i < options.visibility.size() && options.visibility[i].tolerance >= 0;
    out.visibility.emplace_back();
    if (!soft) continue;
    const std::string vis = outputs::visibility_name(i, out.masks.size());
    if (!std::filesystem::exists(candidate_dir / vis, ec))
      throw CompareError(CompareError::Kind::BadInput, (candidate_dir / vis).string() +
                                                           ": no such file (a soft technique's lit fraction, 8-bit grey, "
                                                           "beside its mask)");
    const Image8 covered = read_image8(reference_dir / outputs::kCoveredName, 1, ref.width, ref.height);
    const std::vector<float> fraction =
        outputs::read_exr(reference_dir / outputs::per_light_name("visibility", "exr", i, out.masks.size()), ref.width, ref.height);
    const Image8 cand_vis = read_image8(candidate_dir / vis, 1, ref.width, ref.height);
    out.visibility.back() =
        compare_visibility(fraction, covered, cand_vis, cand, options.visibility[i], options.explain_visibility, i,
                           options.visibility_texel_shift);
    if (!out.visibility_total) out.visibility_total = VisibilityMetrics{};
    *out.visibility_total += out.visibility.back()->metrics;
  }
  out.judgement = judge(out.total, threshold);
  if (out.visibility_total) judge_visibility(*out.visibility_total, out.judgement);
  return out;
}

void judge_visibility(const VisibilityMetrics& m, Judgement& j) {
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
