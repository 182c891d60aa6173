// shadowref/reference/flush_denormals.hpp — flush-to-zero and denormals-are-zero for one scope.
//
// Embree asks for both on the threads that trace (docs/dependencies.md); the reference's ray
// builders run under them too, whoever calls them, so that a ray's bits never depend on the
// caller's floating-point mode. The mode is per thread and changes other float results there, so
// it is restored at the end of the scope, leaving TBB's worker threads as we found them. Public for
// the benchmarks' bare Embree loops, which must trace in the very mode the reference does.
#pragma once

#include <xmmintrin.h>

namespace shadowref::reference {

class FlushDenormalsGuard {
 public:
  FlushDenormalsGuard() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ (bit 15) | DAZ (bit 6)
  ~FlushDenormalsGuard() { _mm_setcsr(saved_); }
  FlushDenormalsGuard(const FlushDenormalsGuard&) = delete;
  FlushDenormalsGuard& operator=(const FlushDenormalsGuard&) = delete;

 private:
  unsigned saved_;
};

}  // namespace shadowref::reference
