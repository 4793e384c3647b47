// What a job's progress events say to a person: the phase in words, how far along it is
// (a fraction, when known) and a detail (rows, rays/s, iteration, residual, ETA). Shared by
// the terminal (`radflux watch`) and the browser view (`radflux view`).
#pragma once

#include <chrono>
#include <string>

#include "radflux/v1/job.pb.h"

namespace radflux::cli {

// One event in words.
struct ProgressWords {
  std::string phase;      // "computing form factors", "solving", "succeeded", ...
  double fraction = -1;   // of the current phase in [0, 1]; -1 when unknown
  double eta_seconds = 0; // of the current phase; 0 when unknown
  std::string detail;     // "rows 6912/7989, 1.2M rays/s, ETA 3 s"
};

// Follows one job's events. The solve's fraction is the progress of log(residual) from the
// first solve residual seen to the job's tolerance, and its ETA extrapolates that progress
// linearly in time; the rows' ETA is the server's.
class JobProgress {
 public:
  // `tolerance`: the job's stopping residual (<= 0: unknown, then no solve fraction).
  explicit JobProgress(double tolerance) : tolerance_(tolerance) {}
  // Folds in one event (not a snapshot) received at `now`; returns what it says.
  ProgressWords Update(const v1::JobEvent& event, std::chrono::steady_clock::time_point now);

 private:
  double SolveFraction(double residual) const;
  double tolerance_;
  double first_residual_ = 0;  // of the first solve event seen (0: none yet)
  std::chrono::steady_clock::time_point first_time_;
};

// A duration for a person: "42 s", "3 min 5 s", "2 h 10 min".
std::string DescribeSeconds(double seconds);

}  // namespace radflux::cli
