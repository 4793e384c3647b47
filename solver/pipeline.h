// The whole computation of one job, as a library: scene -> patches -> Embree scene ->
// form-factor rows -> solve. The CLI runs RunJob in-process; the server runs the same
// phases itself (rows block by block, checkpointed) using PrepareJob and the pieces.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/cancel.h"
#include "solver/formfactor/form_factor_options.h"
#include "solver/formfactor/row_builder.h"
#include "solver/hierarchical/hierarchical.h"
#include "solver/mesh/adaptive_refine.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/scene.h"
#include "solver/solve/solver.h"

namespace radflux {

struct JobOptions {
  MeshOptions mesh;
  FormFactorOptions form_factors;
  SolverOptions solver;  // its cancel/initial pointers are the caller's to set
  HierarchicalOptions hierarchical;  // enabled: RunJob solves hierarchically (issue 7)
  AdaptiveOptions adaptive;          // passes > 0: RunJob meshes adaptively (issue 7)
};

// Checks option values (ranges, hemicube resolution even, ...); INVALID_ARGUMENT names
// the option.
absl::Status ValidateJobOptions(const JobOptions& options);

// A job after meshing and the Embree build: everything the row and solve phases need.
struct PreparedJob {
  Scene scene;
  PatchMesh mesh;
  MeshStats mesh_stats;
  PatchAttributes attributes;
  std::unique_ptr<EmbreeRayCaster> caster;
  RowContext rows;  // points into mesh and caster: PreparedJob is not copyable or movable
  double load_seconds = 0, mesh_seconds = 0, embree_seconds = 0;

  PreparedJob() = default;
  PreparedJob(const PreparedJob&) = delete;
  PreparedJob& operator=(const PreparedJob&) = delete;
};

// Validates the scene and options, subdivides, builds the Embree scene.
absl::StatusOr<std::unique_ptr<PreparedJob>> PrepareJob(Scene scene, const JobOptions& options);

// Upper estimate of a job's peak memory in bytes for n patches (mesh, Embree, rows, solver),
// so a server can refuse before any work starts.
uint64_t EstimateJobBytes(const Scene& scene, const JobOptions& options);

struct JobTimings {
  double load = 0, mesh = 0, embree = 0, rows = 0, solve = 0;  // seconds per phase
};

struct JobResult {
  std::unique_ptr<PreparedJob> job;
  CsrMatrix form_factors;
  RowBlockStats row_stats;
  SolveResult solve;
  JobTimings timings;
};

struct JobCallbacks {
  PhaseProgress phase;  // "rows" progress; returning false cancels
  SolveCallback solve;  // per-iteration progress and snapshots
};

// Runs all phases in-process on options.form_factors.threads threads.
absl::StatusOr<JobResult> RunJob(Scene scene, const JobOptions& options,
                                 const JobCallbacks& callbacks = {});

}  // namespace radflux
