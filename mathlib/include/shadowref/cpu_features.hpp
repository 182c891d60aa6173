// shadowref/cpu_features.hpp — what the running x86-64 CPU can do, asked once: the switch between
// the baseline loops (SSE2, which every x86-64 CPU has, so the library needs no -march) and the
// AVX2 ones of transform_points.hpp and silhouette.hpp. Elsewhere both answer false.
#pragma once

namespace shadowref {

#if defined(__x86_64__)
inline bool cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
inline bool cpu_has_avx2_fma() {
  static const bool has = cpu_has_avx2() && __builtin_cpu_supports("fma");
  return has;
}
#else
inline bool cpu_has_avx2() { return false; }
inline bool cpu_has_avx2_fma() { return false; }
#endif

}  // namespace shadowref
