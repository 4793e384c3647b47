#include "server/jobs/row_budget.h"

#include "absl/strings/str_cat.h"
#include "solver/core/physical_memory.h"

namespace radflux {

uint64_t PerJobMemoryLimit(uint64_t configured) {
  if (configured > 0) return configured;
  const uint64_t physical = PhysicalMemoryBytes();
  return physical > 0 ? physical / 2 : 8ull << 30;
}

absl::StatusOr<uint64_t> RowMemoryBudget(uint64_t patches, const JobOptions& options,
                                         uint64_t max_memory) {
  JobOptions in_memory = options;
  in_memory.spill = RowSpillOptions{};
  const uint64_t bytes = EstimateJobBytes(patches, in_memory);
  if (bytes <= max_memory) return 0;
  const std::string needs = absl::StrCat("job needs an estimated ", bytes,
                                         " bytes with its rows in memory; this server allows ",
                                         max_memory, " per job (--max-memory)");
  if (options.hierarchical.enabled || options.adaptive.passes > 0) {
    return absl::ResourceExhaustedError(
        absl::StrCat(needs, ", and hierarchical or adaptive jobs cannot spill rows to disk"));
  }
  if (!StreamsRows(options.solver.method)) {
    return absl::ResourceExhaustedError(
        absl::StrCat(needs, ", and solver ", std::string(SolverName(options.solver.method)),
                     " cannot spill rows to disk (jacobi, gauss_seidel or auto can)"));
  }
  // The estimate with a 1-byte row budget is everything but the rows kept in memory.
  JobOptions spilled = in_memory;
  spilled.spill.memory_limit = 1;
  const uint64_t rest = EstimateJobBytes(patches, spilled) - 1;
  if (rest >= max_memory) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "job needs an estimated ", rest + 1, " bytes even with its rows spilled to disk; ",
        "this server allows ", max_memory, " per job (--max-memory)"));
  }
  return max_memory - rest;
}

}  // namespace radflux
