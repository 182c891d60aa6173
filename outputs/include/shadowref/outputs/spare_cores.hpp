// shadowref/outputs/spare_cores.hpp — the threads a command uses when --jobs is 0: the cores the
// machine can spare. "All cores" on a shared machine (CI runners, a build beside the tests) competes
// with every other job and slows all of them; the one-minute load average says how many cores are
// busy, so a command takes the rest, and at least one. Resolved once per command, before our own
// threads add to the load.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <thread>

namespace shadowref::outputs {

// The cores left by `load` busy ones out of `cores`, rounded to the nearest, at least 1.
inline int spare_cores(unsigned cores, double load) {
  const double spare = static_cast<double>(std::max(1u, cores)) - std::max(0.0, load);
  return std::max(1, static_cast<int>(std::lround(spare)));
}

// This machine's: std::thread::hardware_concurrency() less getloadavg()'s one-minute average (all
// cores where the system does not say).
inline int spare_cores() {
  double load[1] = {0.0};
  const bool known = ::getloadavg(load, 1) == 1;
  return spare_cores(std::thread::hardware_concurrency(), known ? load[0] : 0.0);
}

}  // namespace shadowref::outputs
