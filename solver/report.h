// The job report: what was asked, what it cost, and the numbers behind the answer
// (patch and matrix sizes, time per phase, rays per second, residual history, energy
// balance), as JSON for scripts and benches.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "solver/pipeline.h"
#include "solver/solve/energy_balance.h"

namespace radflux {

// The energy balance of a finished job, computed once (one pass over the rows, unless the
// strategy left its own in result.solved_balance) and kept in result.solved_balance, so the
// report and the caller's verdict (a balance that is off is an exit status of its own, or a
// job flagged so) read the same numbers.
const absl::StatusOr<EnergyBalance>& SettleEnergyBalance(JobResult& result,
                                                         const JobOptions& options);

// The report as JSON; settles the energy balance (SettleEnergyBalance) if not yet done.
nlohmann::json MakeJobReport(JobResult& result, const JobOptions& options,
                             const std::string& scene_name);

}  // namespace radflux
