// The host's CPU time of the whole process (every thread's user and system
// time): what a frame costs the host whatever its load, beside the wall
// clock, which also counts the time other jobs had the cores.
#pragma once

#include <ctime>

namespace mc1 {

inline double process_cpu_seconds() {
  timespec ts{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return 0;
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

}  // namespace mc1
