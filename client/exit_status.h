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

}  // namespace radflux::cli
