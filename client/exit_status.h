// How a verb ends: one line on stderr naming the verb and the problem, and an exit code
// (2 for bad input the user can fix, 3 for a solve that stopped short of its tolerance,
// 1 for everything else).
#pragma once

#include <cstdio>
#include <string>

#include "absl/status/status.h"

namespace radflux::cli {

// Exit code of a solve (local, or a job's result/watch) that ended without reaching
// --tolerance: its outputs are written, but B is not as accurate as asked.
inline constexpr int kExitNotConverged = 3;

// Prints the one line saying a solve stopped short (`radflux VERB: not converged: ...`
// with the residual reached) and returns kExitNotConverged.
inline int ReportNotConverged(const char* verb, int iterations, double residual,
                              double tolerance) {
  std::fprintf(stderr,
               "radflux %s: not converged: residual %.3g after %d iterations, tolerance %.3g "
               "(outputs written)\n",
               verb, residual, iterations, tolerance);
  return kExitNotConverged;
}

// Prints `radflux VERB: message` for a failed status and returns the exit code; 0 when ok.
inline int ReportStatus(const char* verb, const absl::Status& status) {
  if (status.ok()) return 0;
  std::fprintf(stderr, "radflux %s: %s\n", verb, std::string(status.message()).c_str());
  return status.code() == absl::StatusCode::kInvalidArgument ? 2 : 1;
}

// The same for a service job whose solve stopped short: `radflux VERB: job ID not converged:
// ...` with the server's message (it gives the residual reached; the job's result is there
// as for any SUCCEEDED job); returns kExitNotConverged.
inline int ReportJobNotConverged(const char* verb, const std::string& job_id,
                                 const std::string& message) {
  std::fprintf(stderr, "radflux %s: job %s %s\n", verb, job_id.c_str(),
               message.empty() ? "not converged" : message.c_str());
  return kExitNotConverged;
}

}  // namespace radflux::cli
