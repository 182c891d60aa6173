// simd_path.cpp — the CPU check behind best_simd_path() (simd_path.hpp).
#include "shadowref/reference/simd_path.hpp"

namespace shadowref::reference {

bool cpu_runs(SimdPath path) {
  if (path == SimdPath::Baseline) return true;
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

SimdPath best_simd_path() {
  static const SimdPath best = cpu_runs(SimdPath::Avx2Fma) ? SimdPath::Avx2Fma : SimdPath::Baseline;
  return best;
}

}  // namespace shadowref::reference
