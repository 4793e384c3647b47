// The job report: what was asked, what it cost, and the numbers behind the answer
// (patch and matrix sizes, time per phase, rays per second, residual history, energy
// balance), as JSON for scripts and benches.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "solver/pipeline.h"
#include "solver/solve/energy_balance.h"

namespace radflux {

nlohmann::json MakeJobReport(const JobResult& result, const JobOptions& options,
                             const std::string& scene_name);

}  // namespace radflux
