// Which options of a view-factor job apply to it, by the flag names of `radflux viewfactors`
// (the names scripts use and error messages give), so that the local command and the service
// (`radflux submit --viewfactors`, which derives the names from the fields a request sets)
// resolve the integration alike and refuse the same options with the same message.
#pragma once

#include <span>
#include <string>

#include "absl/status/status.h"
#include "solver/formfactor/view_factor_job.h"

namespace radflux {

// Solve options that mean nothing for view factors (issue 23: "no solver options").
inline constexpr const char* kViewFactorSolverOnlyFlags[] = {
    "--solver",           "--tolerance",       "--max-iterations",     "--link-epsilon",
    "--clusters",         "--min-element-area", "--adaptive-passes", "--adaptive-threshold",
    "--emit"};
// Import rules, which .stl and .vs3 models are read without.
inline constexpr const char* kViewFactorImportFlags[] = {"--max-reflectance", "--strict",
                                                         "--two-sided", "--curve-segments"};
// The options of patch-row integration, and of adaptive (per surface pair) integration.
inline constexpr const char* kViewFactorPatchFlags[] = {
    "--patches", "--max-edge", "--form-factors", "--rays", "--hemicube-res", "--samples",
    "--cutoff",  "--seed"};
inline constexpr const char* kViewFactorAdaptiveFlags[] = {"--vf-tolerance", "--far-ratio",
                                                           "--middle-ratio", "--memory-limit"};

// The integration a job runs: `requested` unless kAuto; kAuto is patches when --form-factors
// is among `given`, else adaptive when every surface of `scene` (by `by`) is one face, else
// patches.
ViewFactorIntegration ResolveViewFactorIntegration(ViewFactorIntegration requested,
                                                   std::span<const std::string> given,
                                                   const Scene& scene, SurfaceGrouping by);

// INVALID_ARGUMENT naming the first of `given` that does nothing for a job on `model_path`
// (its extension decides whether import rules apply) with integration `resolved`
// (`requested` as asked, for the message).
absl::Status CheckViewFactorFlags(std::span<const std::string> given,
                                  const std::string& model_path,
                                  ViewFactorIntegration requested,
                                  ViewFactorIntegration resolved);

}  // namespace radflux
