// visibility.cpp — soft shadows judged in visibility units (visibility.hpp).
#include "shadowref/compare/visibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "shadowref/compare/compare.hpp"

namespace shadowref::compare {
namespace {

enum Code : std::uint8_t { kNotJudged, kWithin, kExplained, kUnexplained };

}  // namespace

double visibility_sampling_tolerance(int reference_samples, int candidate_taps) {
  return 1.0 / std::max(1, reference_samples) + 1.0 / std::max(1, candidate_taps) + 0.5 / 255.0;
}

double visibility_mean_error_bound(int reference_samples, int candidate_taps) {
  return 0.25 / std::max(1, reference_samples) + 0.25 / std::max(1, candidate_taps);
}

VisibilityBounds visibility_bounds(int reference_samples, int candidate_taps, outputs::Sampling sampling) {
  VisibilityBounds b;
  if (sampling == outputs::Sampling::Grid) {
    b.tolerance = visibility_sampling_tolerance(reference_samples, candidate_taps);
    b.mean_error_bound = visibility_mean_error_bound(reference_samples, candidate_taps);
    return b;
  }
  const double n = std::max(1, reference_samples);
  const double sigma_max = 0.5 / std::max(1, candidate_taps);
  b.tolerance = 1.0 / n + 3.0 * sigma_max + 0.5 / 255.0;
  b.mean_error_bound = 0.25 / n + sigma_max;
  b.local_mean_error_bound = 0.25 / n + sigma_max / 3.0;
  return b;
}

double VisibilityMetrics::unexplained_ratio() const {
  return penumbra == 0 ? 0.0 : static_cast<double>(unexplained) / static_cast<double>(penumbra);
}

double VisibilityMetrics::mean_penumbra_error() const {
  return penumbra == 0 ? 0.0 : sum_penumbra_error / static_cast<double>(penumbra);
}

double VisibilityMetrics::mean_penumbra_local_error() const {
  return penumbra == 0 ? 0.0 : sum_penumbra_local_error / static_cast<double>(penumbra);
}

double VisibilityMetrics::mean_penumbra_texel_error() const {
  return penumbra == 0 ? 0.0 : sum_penumbra_texel_error / static_cast<double>(penumbra);
}

double VisibilityMetrics::mean_error_fail() const {
  return penumbra == 0 ? mean_error_bound : sum_penumbra_error_fail / static_cast<double>(penumbra);
}

double VisibilityMetrics::local_mean_error_fail() const {
  return penumbra == 0 ? local_mean_error_bound : sum_penumbra_local_error_fail / static_cast<double>(penumbra);
}

VisibilityMetrics& VisibilityMetrics::operator+=(const VisibilityMetrics& o) {
  judged += o.judged;
  penumbra += o.penumbra;
  beyond_sampling += o.beyond_sampling;
  explained += o.explained;
  unexplained += o.unexplained;
  unexplained_too_light += o.unexplained_too_light;
  unexplained_too_light_core += o.unexplained_too_light_core;
  unexplained_core += o.unexplained_core;
  sum_penumbra_error += o.sum_penumbra_error;
  sum_penumbra_local_error += o.sum_penumbra_local_error;
  sum_penumbra_texel_error += o.sum_penumbra_texel_error;
  sum_penumbra_error_fail += o.sum_penumbra_error_fail;
  sum_penumbra_local_error_fail += o.sum_penumbra_local_error_fail;
  max_error = std::max(max_error, o.max_error);
  mean_error_bound = std::max(mean_error_bound, o.mean_error_bound);
  local_mean_error_bound = std::max(local_mean_error_bound, o.local_mean_error_bound);
  return *this;
}

VisibilityComparison compare_visibility(const std::vector<float>& reference, const outputs::Image8& covered,
                                        const outputs::Image8& candidate, const outputs::Image8& candidate_mask,
                                        const VisibilityBounds& bounds, const VisibilityExplainer* explain,
                                        std::size_t light, const VisibilityTexelShift* texel_shift) {
  const double tolerance = bounds.tolerance;
  const int w = covered.width, h = covered.height;
  const std::size_t n = covered.pixel_count();
  VisibilityComparison out;
  VisibilityMetrics& m = out.metrics;
  m.mean_error_bound = bounds.mean_error_bound;
  m.local_mean_error_bound = bounds.local_mean_error_bound;
  std::vector<std::uint8_t> code(n, kNotJudged);
  std::vector<float> error(n, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      const float r = reference[i];
      if (!outputs::is_flag_set(covered.pixels[i]) || r < 0 || candidate_mask.pixels[i] == outputs::kMaskNoSurface) continue;
      ++m.judged;
      const double c = candidate.pixels[i] / 255.0;
      const double e = c - static_cast<double>(r);
      error[i] = static_cast<float>(e);
      m.max_error = std::max(m.max_error, std::abs(e));
      if (r > 0 && r < 1) {
        ++m.penumbra;
        m.sum_penumbra_error += std::abs(e);
      }
      if (std::abs(e) <= tolerance) {
        code[i] = kWithin;
        continue;
      }
      ++m.beyond_sampling;
      bool explained = false;
      if (explain && *explain) {
        const auto [lo, hi] = (*explain)(light, x, y);
        explained = lo <= hi && c >= lo - tolerance && c <= hi + tolerance;
      }
      code[i] = explained ? kExplained : kUnexplained;
      ++(explained ? m.explained : m.unexplained);
      if (!explained && e > 0) ++m.unexplained_too_light;
    }
  // The local means: e averaged over the judged pixels of the 3 x 3 around each penumbra pixel.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      if (code[i] == kNotJudged || !(reference[i] > 0 && reference[i] < 1)) continue;
      double sum = 0;
      int count = 0;
      for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx) {
          const std::size_t j = static_cast<std::size_t>(yy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(xx);
          if (code[j] == kNotJudged) continue;
          sum += static_cast<double>(error[j]);
          ++count;
        }
      m.sum_penumbra_local_error += std::abs(sum / count);
    }
  // The texel shift, only where this light's means exceed sampling's bounds (a light within them
  // needs none, and the sum over lights stays within the largest bound plus the shifts asked).
  const bool beyond_sampling_means =
      m.mean_penumbra_error() > m.mean_error_bound ||
      (m.local_mean_error_bound > 0 && m.mean_penumbra_local_error() > m.local_mean_error_bound);
  if (beyond_sampling_means && texel_shift && *texel_shift)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        if (code[i] == kNotJudged || !(reference[i] > 0 && reference[i] < 1)) continue;
        // A uniform offset within +-h texels moves the fraction by half its largest change on average.
        m.sum_penumbra_texel_error += 0.5 * (*texel_shift)(light, x, y);
      }
  // Sampling's error and the map's texel offset are independent and zero-mean over a penumbra: they
  // add as variances (for Gaussian errors E|a + b| = sqrt(E|a|² + E|b|²) exactly).
  const double p = static_cast<double>(m.penumbra);
  m.sum_penumbra_error_fail = p * std::hypot(m.mean_error_bound, m.mean_penumbra_texel_error());
  m.sum_penumbra_local_error_fail = p * std::hypot(m.local_mean_error_bound, m.mean_penumbra_texel_error());
  // Cores: a (2 kCoreRadius + 1)² block of unexplained pixels (compare.hpp).
  std::vector<std::uint8_t> unexplained(n);
  for (std::size_t i = 0; i < n; ++i) unexplained[i] = code[i] == kUnexplained;
  m.unexplained_core = count_cores(unexplained, w, h, m.unexplained);
  for (std::size_t i = 0; i < n; ++i) unexplained[i] = unexplained[i] && error[i] > 0;
  m.unexplained_too_light_core = count_cores(unexplained, w, h, m.unexplained_too_light);
  // The error image over the dimmed reference fraction.
  out.error = outputs::Image8{w, h, 3, std::vector<std::uint8_t>(3 * n)};
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t* px = &out.error.pixels[3 * i];
    const double grey = reference[i] < 0 ? 0.15 : 0.2 + 0.3 * static_cast<double>(reference[i]);
    double rgb[3] = {grey, grey, grey};
    const double strength = std::min(1.0, 0.35 + 1.3 * std::abs(static_cast<double>(error[i])));
    const std::uint8_t* colour = nullptr;
    if (code[i] == kNotJudged && reference[i] >= 0) colour = error_colour(ErrorClass::Undecided).data();
    if (code[i] == kExplained) colour = error_colour(ErrorClass::Texel).data();
    if (code[i] == kUnexplained) colour = (error[i] < 0 ? error_colour(ErrorClass::FalseShadow) : error_colour(ErrorClass::FalseLight)).data();
    if (colour) {
      const double a = code[i] == kNotJudged ? 1.0 : strength;
      for (int ch = 0; ch < 3; ++ch) rgb[ch] = a * colour[ch] / 255.0 + (1 - a) * rgb[ch];
    }
    for (int ch = 0; ch < 3; ++ch) px[ch] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(rgb[ch], 0.0, 1.0)));
  }
  return out;
}

}  // namespace shadowref::compare
