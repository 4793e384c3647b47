// RunJob's hierarchical and adaptive paths: the same JobResult as a uniform job, with the
// conforming leaf mesh as job->mesh and B per patch, so every output applies unchanged.
#pragma once

#include "absl/status/statusor.h"
#include "solver/pipeline.h"

namespace radflux {

// options.hierarchical.enabled: form_factors in the result is n x n with EMPTY rows (the
// link set is not expanded to patches), so the report's energy balance does not apply.
// Partly transparent faces (Material::opacity < 1) let light through as in a uniform job
// (hierarchical.h).
absl::StatusOr<JobResult> RunHierarchicalJob(Scene scene, const JobOptions& options,
                                             const JobCallbacks& callbacks);

// options.adaptive.passes > 0: rows are expanded from leaves to the display patches
// (F_ij = F_leaf(i) leaf(j) * A_j / A_leaf(j)), so the report's energy balance applies.
absl::StatusOr<JobResult> RunAdaptiveJob(Scene scene, const JobOptions& options,
                                         const JobCallbacks& callbacks);

}  // namespace radflux
