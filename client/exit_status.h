// How a verb ends: one line on stderr naming the verb and the problem, and an exit code
// (2 for bad input the user can fix, 3 for a solve that stopped short of its tolerance,
// 4 for a solve whose energy balance is off or view factors whose rows sum above 1, 1 for
// everything else).
#pragma once

#include <cstdio>
#include <string>

#include "absl/status/status.h"

namespace radflux::cli {

// Exit code of a solve (local, or a job's result/watch) that ended without reaching
// --tolerance: its outputs are written, but B is not as accurate as asked.
inline constexpr int kExitNotConverged = 3;
// Exit code of a converged solve (local, or a job's result/watch) whose energy balance is
// off: emitted != absorbed + escaped beyond the rows' noise. Its outputs are written, but
// the rows or the scene are suspect (overlapping faces, rows that are not reciprocal).
inline constexpr int kExitEnergyImbalance = 4;
// Exit code of `radflux viewfactors` when some row sums to more than 1 beyond its error
// allowance (the same "outputs written, but suspect" code as an energy imbalance).
inline constexpr int kExitRowSumOver = kExitEnergyImbalance;

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

// Prints `radflux VERB: energy balance off by ...` (the EnergyBalance::OffMessage) and
// returns kExitEnergyImbalance.
inline int ReportEnergyImbalance(const char* verb, const std::string& message) {
  std::fprintf(stderr, "radflux %s: %s (outputs written)\n", verb, message.c_str());
  return kExitEnergyImbalance;
}

// The exit code a SUCCEEDED job's verdict gives (a v1::Job or its final v1::JobEvent):
// kExitNotConverged, else kExitEnergyImbalance, else 0. An unset flag (a job finished
// before the flag existed) counts as fine.
template <class JobOrEvent>
int SucceededJobExitCode(const JobOrEvent& job) {
  if (job.has_converged() && !job.converged()) return kExitNotConverged;
  if (job.has_energy_balance_ok() && !job.energy_balance_ok()) return kExitEnergyImbalance;
  return 0;
}

// The line for a service job whose verdict is not 0: `radflux VERB: job ID MESSAGE`, the
// server's message saying what fell short (the residual reached, the balance that is off;
// the job's result is there as for any SUCCEEDED job); returns `code`.
inline int ReportJobShortfall(const char* verb, const std::string& job_id,
                              const std::string& message, int code) {
  std::fprintf(stderr, "radflux %s: job %s %s\n", verb, job_id.c_str(),
               message.empty() ? "fell short of its tolerance or its energy balance"
                               : message.c_str());
  return code;
}

}  // namespace radflux::cli
