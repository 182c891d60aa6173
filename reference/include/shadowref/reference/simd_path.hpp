// shadowref/reference/simd_path.hpp — which compiled variant of the ray builders runs.
//
// The ray builders (camera_rays.hpp, shadow_ray.hpp) are compiled twice from one source: for the
// x86-64 baseline (SSE2, 4 float lanes) and for AVX2 + FMA (8 lanes). Both variants give the same
// bits: the builders are plain IEEE +, −, ×, ÷ and square roots in a fixed order, compiled with
// -ffp-contract=off, so that the FMA variant fuses nothing (test: ray_bits_test). Choosing one at
// run time is therefore a choice of speed only, never of result.
#pragma once

namespace shadowref::reference {

enum class SimdPath {
  Baseline,  // SSE2: every x86-64 CPU
  Avx2Fma,   // AVX2 and FMA, where the CPU has both
};

// The fastest path this CPU runs (checked once).
SimdPath best_simd_path();
// Whether this CPU can run `path`.
bool cpu_runs(SimdPath path);

}  // namespace shadowref::reference
