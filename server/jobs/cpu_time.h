// CpuMs and MsBetween: CPU and wall time of the server's threads, for the debug log's cost
// lines (what a job and its watchers cost; bench/watcher_cost.sh reads them); NowUnixMs for
// the times a job records.
#pragma once

#include <time.h>

#include <chrono>
#include <cstdint>

namespace radflux {

// CPU milliseconds of `clock` (CLOCK_THREAD_CPUTIME_ID: the calling thread;
// CLOCK_PROCESS_CPUTIME_ID: every thread of the server, ended ones included), ns resolution.
inline double CpuMs(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// Wall milliseconds from a to b.
inline double MsBetween(std::chrono::steady_clock::time_point a,
                        std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Milliseconds since the Unix epoch (wall clock).
inline int64_t NowUnixMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace radflux
