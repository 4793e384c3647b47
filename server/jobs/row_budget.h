// How a job fits a server's memory limit per job (--max-memory, against EstimateJobBytes):
// with its rows in memory, or else with its rows spilled to disk beyond a budget (jacobi,
// gauss_seidel and auto only), or not at all.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "solver/pipeline.h"

namespace radflux {

// Bytes a job may use: `configured` (--max-memory) when > 0, else half the machine's RAM.
uint64_t PerJobMemoryLimit(uint64_t configured);

// 0 when the job fits `max_memory` bytes with its rows in memory; otherwise the bytes of
// rows it may keep in memory, max_memory minus the rest of its estimate spilled, while the
// other rows spill. RESOURCE_EXHAUSTED, naming the reason and --max-memory, when it does
// not fit even spilled or its options cannot spill (cg, southwell, direct, hierarchical,
// adaptive).
// `patches`: the job's patch count (LoadedScene::PatchCount).
absl::StatusOr<uint64_t> RowMemoryBudget(uint64_t patches, const JobOptions& options,
                                         uint64_t max_memory);

}  // namespace radflux
