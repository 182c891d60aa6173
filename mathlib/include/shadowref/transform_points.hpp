// shadowref/transform_points.hpp — a batch of homogeneous points through one 4×4 matrix (a vertex
// buffer through the shadow matrix of shadow_matrix.hpp, or any other), on the CPU.
//
// Convention: canonical column vectors, out_i = M in_i, float, each point four contiguous floats
// (x, y, z, w) — the layout of a float4 vertex buffer; `in` and `out` may be the same buffer but
// must not otherwise overlap. No homogeneous divide: the planar shadow of v is (M v).xyz / (M v).w,
// done by the GPU after clipping (a point beyond the light gets w < 0, see shadow_matrix.hpp).
//
// Why not Eigen's `out = M * in` over a 4×N map: for a dynamic N, Eigen evaluates it as a general
// matrix product (packing both operands); measured 2.5x slower than this loop up to 100k points and
// even at 10M, where both stream memory (bench/math_bench.cpp). The loop is the textbook one, column by column: out = c0·x + c1·y + c2·z
// + c3·w with the matrix's four columns in registers and each coordinate broadcast. Two versions:
// SSE2 (the x86-64 baseline: one point per 128-bit register) and, on CPUs that have them (checked
// once, at run time: cpu_features.hpp), AVX2 + FMA (two points per 256-bit register;
// the broadcasts are in-lane permutes, which is what bounds it on data in L1).
// Rounding: the SSE2 path rounds each product and sum, (c0·x + c1·y) + (c2·z + c3·w); the FMA
// path is one chain of three fused multiply-adds (one fewer instruction per point than a tree,
// measured faster), so the paths may differ in the last bits; both are within 4 ε Σ|m_rc v_c| of
// the exact product of the floats (a 4-term dot product's error bound).
//
// Cost: 32 bytes of memory traffic per point; on large batches the loop runs at the speed of
// streaming those bytes (bench/README.md, "Goals", point batch).
#pragma once

#include <cstddef>

#include "shadowref/conventions.hpp"
#include "shadowref/cpu_features.hpp"

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define SHADOWREF_TRANSFORM_POINTS_X86 1
#endif

namespace shadowref {

namespace detail {

// Column-major copy of M (the layout both SIMD paths load columns from).
inline void matrix_columns(const Mat4<float>& m, float (&cols)[16]) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) cols[4 * c + r] = m(r, c);
}

inline void transform_points_scalar(const float (&m)[16], const float* in, float* out, std::size_t first,
                                    std::size_t n) {
  for (std::size_t i = first; i < n; ++i) {
    const float x = in[4 * i], y = in[4 * i + 1], z = in[4 * i + 2], w = in[4 * i + 3];
    for (int r = 0; r < 4; ++r) out[4 * i + r] = (m[r] * x + m[4 + r] * y) + (m[8 + r] * z + m[12 + r] * w);
  }
}

#ifdef SHADOWREF_TRANSFORM_POINTS_X86
inline void transform_points_sse2(const float (&m)[16], const float* in, float* out, std::size_t n) {
  const __m128 c0 = _mm_loadu_ps(m), c1 = _mm_loadu_ps(m + 4), c2 = _mm_loadu_ps(m + 8), c3 = _mm_loadu_ps(m + 12);
  for (std::size_t i = 0; i < n; ++i) {
    const __m128 p = _mm_loadu_ps(in + 4 * i);
    const __m128 xy = _mm_add_ps(_mm_mul_ps(c0, _mm_shuffle_ps(p, p, 0x00)), _mm_mul_ps(c1, _mm_shuffle_ps(p, p, 0x55)));
    const __m128 zw = _mm_add_ps(_mm_mul_ps(c2, _mm_shuffle_ps(p, p, 0xAA)), _mm_mul_ps(c3, _mm_shuffle_ps(p, p, 0xFF)));
    _mm_storeu_ps(out + 4 * i, _mm_add_ps(xy, zw));
  }
}

__attribute__((target("avx2,fma"))) inline void transform_points_avx2(const float (&m)[16], const float* in,
                                                                       float* out, std::size_t n) {
  // Each 256-bit register holds two points; a column broadcast to both halves serves both.
  const __m256 c0 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(m));
  const __m256 c1 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(m + 4));
  const __m256 c2 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(m + 8));
  const __m256 c3 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(m + 12));
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    const __m256 p = _mm256_loadu_ps(in + 4 * i);
    __m256 r = _mm256_mul_ps(c0, _mm256_permute_ps(p, 0x00));
    r = _mm256_fmadd_ps(c1, _mm256_permute_ps(p, 0x55), r);
    r = _mm256_fmadd_ps(c2, _mm256_permute_ps(p, 0xAA), r);
    _mm256_storeu_ps(out + 4 * i, _mm256_fmadd_ps(c3, _mm256_permute_ps(p, 0xFF), r));
  }
  transform_points_scalar(m, in, out, i, n);  // an odd last point
}

#endif

}  // namespace detail

// out[4i .. 4i+3] = M · in[4i .. 4i+3] for i < n (column vectors, float4 points). See the header
// comment for the layout, the rounding and the cost. No allocation.
inline void transform_points(const Mat4<float>& m, const float* in, float* out, std::size_t n) {
  float cols[16];
  detail::matrix_columns(m, cols);
#ifdef SHADOWREF_TRANSFORM_POINTS_X86
  if (cpu_has_avx2_fma())
    detail::transform_points_avx2(cols, in, out, n);
  else
    detail::transform_points_sse2(cols, in, out, n);
#else
  detail::transform_points_scalar(cols, in, out, 0, n);
#endif
}

}  // namespace shadowref
