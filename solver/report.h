// The job report: what was asked, what it cost, and the numbers behind the answer
// (patch and matrix sizes, time per phase, rays per second, residual history, energy
// balance), as JSON for scripts and benches.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "solver/pipeline.h"
#include "solver/solve/energy_balance.h"

namespace radflux {

// Energy balance is checked against this relative tolerance in the report's "ok" flag.
inline constexpr double kEnergyBalanceTolerance = 0.005;

nlohmann::json MakeJobReport(const JobResult& result, const JobOptions& options,
                             const std::string& scene_name);

}  // namespace radflux
