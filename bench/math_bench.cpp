// math_bench.cpp — shadow matrix and infinite projection construction, and a batch of N points
// through the shadow matrix: ours (transform_points.hpp) against Eigen's product, a GLM loop and a
// plain scalar loop, with the streaming ceiling: the same bytes moved by the same loads and stores
// and no arithmetic (no transform can beat it). Every batch variant reads N float4 points and
// writes N float4 results (32 bytes per point). Goal: ours >= 0.8 of the ceiling.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <immintrin.h>

#include <cstring>
#include <glm/glm.hpp>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/shadow_matrix.hpp"
#include "shadowref/transform_points.hpp"

namespace {

using shadowref::Mat4;
using shadowref::Vec4;

void BM_ShadowMatrix(benchmark::State& state) {
  const auto plane = shadowref::plane_from_coefficients(0.1, 1.0, 0.2, -0.5).value();
  Vec4<double> light(2, 6, 1, 1);
  for (auto _ : state) {
    benchmark::DoNotOptimize(light);
    auto s = shadowref::shadow_matrix(plane, light);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShadowMatrix);

void BM_PerspectiveInfinite(benchmark::State& state) {
  double fovy = std::numbers::pi / 4;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fovy);
    auto p = shadowref::perspective_infinite(fovy, 16.0 / 9.0, 0.1, shadowref::kOpenGL, 4.8e-7);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PerspectiveInfinite);

// N homogeneous points (x, y, z, 1), float, contiguous: the layout a vertex buffer has.
struct Batch {
  std::vector<float> in, out;
  Mat4<float> s;
  explicit Batch(std::size_t n) : in(4 * n), out(4 * n) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(-10.0f, 10.0f);
    for (std::size_t i = 0; i < n; ++i) {
      in[4 * i] = u(rng);
      in[4 * i + 1] = u(rng) + 11.0f;
      in[4 * i + 2] = u(rng);
      in[4 * i + 3] = 1.0f;
    }
    const auto plane = shadowref::plane_from_coefficients(0.0f, 1.0f, 0.0f, 0.0f).value();
    s = shadowref::shadow_matrix(plane, Vec4<float>(2, 30, 1, 1)).value();
  }
};

void finish_batch(benchmark::State& state, std::size_t n) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(n));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(32 * n));
}

void BM_PointBatch_Ours(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Batch b(n);
  for (auto _ : state) {
    shadowref::transform_points(b.s, b.in.data(), b.out.data(), n);
    benchmark::ClobberMemory();
  }
  finish_batch(state, n);
}

// Eigen's own product over 4 × N maps (a general matrix product for a dynamic N).
void BM_PointBatch_Eigen(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Batch b(n);
  const Eigen::Map<const Eigen::Matrix<float, 4, Eigen::Dynamic>> in(b.in.data(), 4, static_cast<Eigen::Index>(n));
  Eigen::Map<Eigen::Matrix<float, 4, Eigen::Dynamic>> out(b.out.data(), 4, static_cast<Eigen::Index>(n));
  for (auto _ : state) {
    out.noalias() = b.s * in;
    benchmark::ClobberMemory();
  }
  finish_batch(state, n);
}

void BM_PointBatch_GLM(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Batch b(n);
  glm::mat4 m;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[c][r] = b.s(r, c);  // GLM is column-major: m[column][row]
  const auto* in = reinterpret_cast<const glm::vec4*>(b.in.data());
  auto* out = reinterpret_cast<glm::vec4*>(b.out.data());
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) out[i] = m * in[i];
    benchmark::ClobberMemory();
  }
  finish_batch(state, n);
}

void BM_PointBatch_Scalar(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Batch b(n);
  float m[16];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[4 * r + c] = b.s(r, c);
  const float* in = b.in.data();
  float* out = b.out.data();
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) {
      const float* p = in + 4 * i;
      float* q = out + 4 * i;
      for (int r = 0; r < 4; ++r) q[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3] * p[3];
    }
    benchmark::ClobberMemory();
  }
  finish_batch(state, n);
}

// The ceiling: what ours could reach if its arithmetic were free — each point's 16 bytes loaded and
// 16 bytes stored with the same instructions ours uses (unaligned vector loads and ordinary,
// write-allocate stores: 256-bit two points at a time where ours takes the AVX2 path, else 128-bit
// one point at a time), in one pass over the same two buffers, allocated and touched before the
// timed loop (Batch's constructor writes both). The loops are kept loops: GCC would otherwise turn
// them into a memcpy call (loop distribution), and glibc's memcpy switches to non-temporal stores
// above a size, which the transform does not use — that mismatch made an earlier memcpy "ceiling"
// slower than the transform at 1M and 10M points. A 128-bit copy is not the ceiling of a 256-bit
// loop either: on this machine it measured slower than the AVX2 transform on 1M points.
__attribute__((optimize("no-tree-loop-distribute-patterns"))) void stream_sse2(const float* in, float* out,
                                                                                std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) _mm_storeu_ps(out + 4 * i, _mm_loadu_ps(in + 4 * i));
}

__attribute__((target("avx2"), optimize("no-tree-loop-distribute-patterns"))) void stream_avx2(const float* in, float* out,
                                                                                             std::size_t n) {
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) _mm256_storeu_ps(out + 4 * i, _mm256_loadu_ps(in + 4 * i));
  if (i < n) _mm_storeu_ps(out + 4 * i, _mm_loadu_ps(in + 4 * i));
}

// The same copies four registers an iteration: on data in L1 a loop of one load and one store is
// bound by the front end, and by where the linker happened to put it (the same source measured 279
// and 146 ns for 1,000 points in two builds; four a loop: 138 - 140 ns), so the ceiling is the
// faster of the two (bench/track takes the smaller median).
__attribute__((optimize("no-tree-loop-distribute-patterns"))) void stream_sse2_unrolled(const float* in, float* out,
                                                                                         std::size_t n) {
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m128 a = _mm_loadu_ps(in + 4 * i), b = _mm_loadu_ps(in + 4 * i + 4);
    const __m128 c = _mm_loadu_ps(in + 4 * i + 8), d = _mm_loadu_ps(in + 4 * i + 12);
    _mm_storeu_ps(out + 4 * i, a), _mm_storeu_ps(out + 4 * i + 4, b);
    _mm_storeu_ps(out + 4 * i + 8, c), _mm_storeu_ps(out + 4 * i + 12, d);
  }
  for (; i < n; ++i) _mm_storeu_ps(out + 4 * i, _mm_loadu_ps(in + 4 * i));
}

__attribute__((target("avx2"), optimize("no-tree-loop-distribute-patterns"))) void stream_avx2_unrolled(
    const float* in, float* out, std::size_t n) {
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 a = _mm256_loadu_ps(in + 4 * i), b = _mm256_loadu_ps(in + 4 * i + 8);
    const __m256 c = _mm256_loadu_ps(in + 4 * i + 16), d = _mm256_loadu_ps(in + 4 * i + 24);
    _mm256_storeu_ps(out + 4 * i, a), _mm256_storeu_ps(out + 4 * i + 8, b);
    _mm256_storeu_ps(out + 4 * i + 16, c), _mm256_storeu_ps(out + 4 * i + 24, d);
  }
  for (; i < n; ++i) _mm_storeu_ps(out + 4 * i, _mm_loadu_ps(in + 4 * i));
}

using Copy = void (*)(const float*, float*, std::size_t);

// A copy loop over the batch: the 256-bit one where ours takes the AVX2 path, else the 128-bit one.
void run_copy(benchmark::State& state, Copy wide, Copy narrow, const char* what) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Batch b(n);
  const bool avx2 = shadowref::cpu_has_avx2_fma();
  for (auto _ : state) {
    (avx2 ? wide : narrow)(b.in.data(), b.out.data(), n);
    benchmark::ClobberMemory();
  }
  finish_batch(state, n);
  state.SetLabel(std::string(avx2 ? "256-bit" : "128-bit") + " loads and stores" + what);
}

void BM_PointBatch_Stream(benchmark::State& state) { run_copy(state, stream_avx2, stream_sse2, ""); }
void BM_PointBatch_StreamUnrolled(benchmark::State& state) {
  run_copy(state, stream_avx2_unrolled, stream_sse2_unrolled, ", four a loop");
}

// glibc's memcpy of the same bytes, for reference only (non-temporal stores on large sizes: a
// different memory path from the transform's, so not its ceiling).
void BM_PointBatch_Memcpy(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Batch b(n);
  for (auto _ : state) {
    std::memcpy(b.out.data(), b.in.data(), 16 * n);
    benchmark::ClobberMemory();
  }
  finish_batch(state, n);
}

void batch_sizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {1000, 10000, 100000, 1000000, 10000000}) b->Arg(n);
  b->ArgName("points");
}
BENCHMARK(BM_PointBatch_Ours)->Apply(batch_sizes);
BENCHMARK(BM_PointBatch_Eigen)->Apply(batch_sizes);
BENCHMARK(BM_PointBatch_GLM)->Apply(batch_sizes);
BENCHMARK(BM_PointBatch_Scalar)->Apply(batch_sizes);
BENCHMARK(BM_PointBatch_Stream)->Apply(batch_sizes);
BENCHMARK(BM_PointBatch_StreamUnrolled)->Apply(batch_sizes);
BENCHMARK(BM_PointBatch_Memcpy)->Apply(batch_sizes);

}  // namespace

BENCHMARK_MAIN();
