// shadowref/outputs/limits.hpp — the sizes every producer and the judge accept, defined once: the
// scene loader, the renderer, candidate.json and every command read them from here, so `render` and
// `conform` accept and refuse the same values with the same line.
#pragma once

#include <string>

namespace shadowref::outputs {

// Pixels per side of an image (a scene's resolution, a mask): 16384² is already a gigabyte of float
// visibility, so anything larger is a typo; the PNG reader refuses larger images from the header.
inline constexpr int kMaxResolution = 16384;

// Texels per side of a shadow map (0: automatic, the fit of mathlib/light_fit.hpp chooses). Below
// 16 a map holds too few texels to fit any light view with its guard band; above 16384 is more than
// any GL implementation's GL_MAX_TEXTURE_SIZE.
inline constexpr int kMinShadowMapSize = 16;
inline constexpr int kMaxShadowMapSize = 16384;

// "" when `texels` is an acceptable shadow map size, else what is wrong with it, as the end of a
// line that names the argument or key ("must be 0 (automatic) or in [16, 16384]").
inline std::string shadow_map_size_problem(long long texels) {
  if (texels == 0 || (texels >= kMinShadowMapSize && texels <= kMaxShadowMapSize)) return "";
  return "must be 0 (automatic) or in [" + std::to_string(kMinShadowMapSize) + ", " + std::to_string(kMaxShadowMapSize) + "]";
}

// Our renderer's guard band (--guard-band): at most this many texels along each side of a light's
// map (engines' atlases keep a few; 64 holds any filter of the catalogue).
inline constexpr int kMaxGuardBandTexels = 64;

// Our renderer's randomized kernel (--random-taps): N taps, a square of 2 .. 8 per axis, so that
// candidate.json's light_taps (taps per axis) says it exactly; 0: the filters' fixed grids.
inline constexpr int kMinRandomTapsPerAxis = 2, kMaxRandomTapsPerAxis = 8;

// "" when `taps` is an acceptable randomized kernel (0, or a square of the bounds above), else what is
// wrong with it, as the end of a line that names the argument.
inline std::string random_taps_problem(long long taps) {
  std::string squares = "0";
  for (long long n = kMinRandomTapsPerAxis; n <= kMaxRandomTapsPerAxis; ++n) {
    if (taps == n * n) return "";
    squares += ", " + std::to_string(n * n);
  }
  if (taps == 0) return "";
  return "must be one of " + squares + " (a square: candidate.json's light_taps is its root)";
}

}  // namespace shadowref::outputs
