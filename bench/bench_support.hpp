// bench_support.hpp — what every suite shares: peak memory counters, and the catalogue folder.
// Benchmarks are never timed tests (bench/README.md): the `bench-smoke` CTest entries only run each
// binary once with a minimal time.
#pragma once

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <fstream>
#include <string>

namespace shadowref::bench {

// The process's peak resident set so far, in MiB (getrusage's ru_maxrss, kilobytes on Linux). It
// only grows, and the suites' repetitions run interleaved at random (bench/track): it is the
// peak of whatever ran before, not of one case. peak_rss_growth_MiB is that of one case.
inline double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

// A field of /proc/self/status in MiB (VmRSS: resident now; VmHWM: the peak since the last reset).
inline double status_mib(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1)) / 1024.0;  // "…:  123 kB"
  return 0.0;
}

// Per run of a benchmark (registered with ->Setup(start_peak_rss)): the resident set before it, and
// the peak reset to it (writing 5 to /proc/self/clear_refs resets VmHWM, Linux >= 4.0).
inline double& rss_at_start() {
  static double mib = 0;
  return mib;
}
inline void start_peak_rss(const benchmark::State&) {
  rss_at_start() = status_mib("VmRSS");
  std::ofstream("/proc/self/clear_refs") << "5";
}

// Counters: peak_rss_MiB (the process's, see above) and peak_rss_growth_MiB, the peak of this run
// over what was resident before it: the case's own inputs and working memory (inputs a suite
// caches across cases count on their first run only, so the median of the repetitions leaves them
// out). Without start_peak_rss registered, the growth is over the resident set at program start.
inline void report_peak_rss(benchmark::State& state) {
  state.counters["peak_rss_MiB"] = benchmark::Counter(peak_rss_mib(), benchmark::Counter::kAvgThreads);
  state.counters["peak_rss_growth_MiB"] =
      benchmark::Counter(status_mib("VmHWM") - rss_at_start(), benchmark::Counter::kAvgThreads);
}

}  // namespace shadowref::bench
