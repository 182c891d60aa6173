// shadowref/compare/visibility.hpp — soft shadows judged in visibility units: a candidate's lit
// fraction (visibility.png, 8-bit) against the reference's (visibility.exr: the mean over the
// light's samples and the pixel's sub-samples), for a light with an area (docs/tolerance-model.md).
//
// Judged pixels: those the reference marks covered by one smooth surface (covered.png) where the
// candidate has a surface too; elsewhere the reference's fraction mixes surfaces a centre sample
// cannot. The error e = candidate − reference. A pixel is
//   within sampling  |e| <= tolerance: the reference samples the light at n × n points and a
//                    filter at n' × n' taps, each fraction off by at most 1/n (1/n') across a
//                    straight boundary, plus the 8-bit step — the caller's per-light tolerance;
//   explained        beyond that, but the candidate's fraction lies within the tolerance of the
//                    range of the true fraction over the declared filter footprint around the pixel
//                    centre's surface point (reference/causes.hpp, visibility_band): what a filter
//                    of that footprint may honestly average over;
//   unexplained      otherwise: red where the candidate is too dark, blue where too light.
// The scale errors are judged against is the penumbra: judged pixels whose reference fraction lies
// strictly between 0 and 1. Its pixel count and the unexplained count both grow with the area of
// the penumbrae, so their ratio means the same at any resolution; so does the mean |e| over it,
// which catches a penumbra of the wrong width, whose error is spread thin over the whole band.
// A filter whose taps are placed anew per pixel at random (candidate.json "sampling": "random": a
// disk rotated by noise) errs by its estimator's spread as well, pixel by pixel and unbiased: a
// mean over a 3 x 3 neighbourhood removes most of it and none of a wrong width, whose error is
// smooth. Its width is therefore judged on those local means, and what only the pixels show is
// noise: a WARN beyond the spread its declared taps may leave, never a wrong penumbra.
// A shadow map reads its casters at texel centres: a correct map moves a penumbra by up to half a
// texel (a whole one on the candidate's own grid), the same way along a straight edge, and where a
// penumbra is only a few texels wide (a small map, a caster near its receiver) that offset is an
// error no sampling bound holds. When a light's mean error exceeds sampling's bound, the judge asks
// each penumbra pixel's texel shift (reference/causes.hpp, visibility_texel_shift: how much the true
// fraction changes over that distance); an offset uniform within it errs by half of it on average,
// and that mean over the penumbra, the texel error, joins sampling's bounds in quadrature (two
// independent zero-mean errors). A map's size is forgiven where it cannot resolve the penumbra; a
// wrong width, spread over the whole band, is not.
// Speed: one pass over the pixels; the explainer only for pixels beyond the tolerance.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/image.hpp"

namespace shadowref::compare {

struct VisibilityMetrics {
  std::size_t judged = 0;            // covered surface pixels, a surface in the candidate too
  std::size_t penumbra = 0;          // judged, reference fraction strictly between 0 and 1: the denominator
  std::size_t beyond_sampling = 0;   // |e| beyond the sampling tolerance
  std::size_t explained = 0;         // of those, within the filter footprint's band
  std::size_t unexplained = 0;       // of those, not
  std::size_t unexplained_too_light = 0;  // of those, the candidate lighter than the truth (blue)
  std::size_t unexplained_core = 0;  // unexplained pixels whose (2 kCoreRadius + 1)² neighbourhood is all unexplained
  std::size_t unexplained_too_light_core = 0;  // the same over the too-light unexplained pixels alone
  double sum_penumbra_error = 0;     // sum of |e| over the penumbra
  double sum_penumbra_local_error = 0;  // sum over the penumbra of |the mean e over the judged 3 x 3 around|
  double sum_penumbra_texel_error = 0;  // sum over the penumbra of half the texel shift (asked only
                                        // where a light's mean exceeds sampling's bound; else 0)
  // Each light's bounds for the means, sampling's and its texel error in quadrature, times its
  // penumbra: summed over lights, a case passes whenever each of its lights does.
  double sum_penumbra_error_fail = 0;
  double sum_penumbra_local_error_fail = 0;
  double max_error = 0;              // largest |e| over the judged pixels
  double mean_error_bound = 0;       // VisibilityBounds::mean_error_bound of the light (the largest over lights)
  double local_mean_error_bound = 0; // VisibilityBounds::local_mean_error_bound (the largest; 0: grid sampling)

  double unexplained_ratio() const;     // unexplained / penumbra (0 without a penumbra)
  double mean_penumbra_error() const;   // sum_penumbra_error / penumbra (0 without a penumbra)
  double mean_penumbra_local_error() const;  // sum_penumbra_local_error / penumbra
  double mean_penumbra_texel_error() const;  // sum_penumbra_texel_error / penumbra
  // The bounds the verdict holds the means to: per light, sampling's and the texel error in
  // quadrature, averaged over the lights' penumbrae (sampling's bound without a penumbra).
  double mean_error_fail() const;
  double local_mean_error_fail() const;
  VisibilityMetrics& operator+=(const VisibilityMetrics& other);
};

struct VisibilityComparison {
  VisibilityMetrics metrics;
  outputs::Image8 error;  // RGB: unexplained red (too dark) / blue (too light), explained orange, brightness ∝ |e|
};

// The sampling tolerance of a light sampled at `reference_samples` × `reference_samples` points by
// the reference and filtered at `candidate_taps` × `candidate_taps` taps by the candidate: across a
// straight boundary each stratified fraction is off by at most one row of its grid, 1/n, and the
// 8-bit fraction by half a step: 1/n + 1/n' + 0.5/255.
double visibility_sampling_tolerance(int reference_samples, int candidate_taps);
// The mean |e| over a penumbra that sampling alone can leave: each stratified fraction's error is
// at most uniform over one step, of mean 1/(4n): 1/(4n) + 1/(4n') (the 8-bit step is negligible).
double visibility_mean_error_bound(int reference_samples, int candidate_taps);

// What sampling alone may leave in a light's fraction (its decision, decide_visibility):
struct VisibilityBounds {
  double tolerance = -1;         // a pixel's |e| within sampling; negative: a light without area, not judged
  double mean_error_bound = 0;   // the mean |e| over the penumbra: beyond it a wrong width (grid), noise (random)
  double local_mean_error_bound = 0;  // random sampling: the mean |local mean e| over the penumbra, beyond
                                      // it a wrong width; 0 for a grid, whose width the plain mean judges
};
// The bounds for a light sampled by the reference at n x n points (`reference_samples`) and filtered
// by the candidate with `candidate_taps` per axis, on a grid or at random:
//   grid    tolerance visibility_sampling_tolerance, mean bound visibility_mean_error_bound;
//   random  N = candidate_taps² taps of an unbiased estimator err by sigma = sqrt(f (1 - f) / N) <=
//           1 / (2 candidate_taps) (the binomial spread, at its widest at f = 1/2). A pixel's
//           tolerance: 1/n + 3 sigma_max + half an 8-bit step (beyond 3 sigma: 0.3 % of a correct
//           penumbra, isolated: no core, a tenth of the 3 % bound); the mean |e| over the penumbra:
//           1/(4n) + sigma_max (E|e| <= sqrt(E e²), Jensen); a 3 x 3 local mean of nine independent
//           pixels: 1/(4n) + sigma_max / 3 (noise correlated the other way, e.g. interleaved
//           gradient noise, leaves less).
VisibilityBounds visibility_bounds(int reference_samples, int candidate_taps, outputs::Sampling sampling);

// [lo, hi] of the true fraction over the declared footprint of pixel (x, y) for light `light`
// (reference::CauseModel::visibility_band); lo > hi: no surface there.
using VisibilityExplainer = std::function<std::pair<double, double>(std::size_t light, int x, int y)>;
// The texel shift of pixel (x, y) for light `light` (reference::CauseModel::visibility_texel_shift):
// the largest change of the true fraction over the declared map's texel uncertainty.
using VisibilityTexelShift = std::function<double(std::size_t light, int x, int y)>;

// Compares one light's fractions. `reference` is width · height floats (−1: no surface), `covered`,
// `candidate` (round(255 · fraction)) and `candidate_mask` (its 128 = no surface) are grey images of
// that size (the caller has checked the sizes). `explain` may be null: nothing is explained;
// `texel_shift` may be null: no map (the means are held to sampling's bounds alone).
VisibilityComparison compare_visibility(const std::vector<float>& reference, const outputs::Image8& covered,
                                        const outputs::Image8& candidate, const outputs::Image8& candidate_mask,
                                        const VisibilityBounds& bounds, const VisibilityExplainer* explain,
                                        std::size_t light, const VisibilityTexelShift* texel_shift = nullptr);

}  // namespace shadowref::compare
