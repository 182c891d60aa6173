// bench_support.hpp — what every suite shares: the process's peak memory as a counter, and the
// catalogue folder. Benchmarks are never timed tests (bench/README.md): the `bench-smoke` CTest
// entries only run each binary once with a minimal time.
#pragma once

#include <benchmark/benchmark.h>
#include <sys/resource.h>

namespace shadowref::bench {

// The process's peak resident set so far, in MiB (getrusage's ru_maxrss, kilobytes on Linux). It
// only grows: on the largest case of a suite (run last) it is the peak of that case.
inline double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

inline void report_peak_rss(benchmark::State& state) {
  state.counters["peak_rss_MiB"] = benchmark::Counter(peak_rss_mib(), benchmark::Counter::kAvgThreads);
}

}  // namespace shadowref::bench
