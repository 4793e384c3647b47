// The whole computation of one job, as a library: scene -> patches -> Embree scene ->
// form-factor rows -> solve. The CLI runs RunJob in-process; the server runs the same
// phases itself (rows block by block, checkpointed) using PrepareJob and the pieces.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/adaptive/adaptive_refine.h"
#include "solver/core/cancel.h"
#include "solver/formfactor/cell_columns.h"
#include "solver/formfactor/form_factor_options.h"
#include "solver/formfactor/row_builder.h"
#include "solver/grouped_mesh.h"
#include "solver/hierarchical/hierarchical.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/scene.h"
#include "solver/solve/energy_balance.h"
#include "solver/solve/solver.h"

namespace radflux {

// Rows beyond a memory budget go to disk and stream back during the solve (jacobi and
// gauss_seidel only).
struct RowSpillOptions {
  uint64_t memory_limit = 0;  // bytes of rows kept in memory; 0 = no limit, nothing spills
  std::string directory;      // spill file location; "" = a fresh directory under $TMPDIR
                              // or /tmp, removed at the end
};

struct JobOptions {
  MeshOptions mesh;
  FormFactorOptions form_factors;
  SolverOptions solver;              // its cancel/initial pointers are the caller's to set
  HierarchicalOptions hierarchical;  // enabled: RunJob solves hierarchically (issue 7)
  AdaptiveOptions adaptive;          // passes > 0: RunJob meshes adaptively (issue 7)
  RowSpillOptions spill;             // memory_limit > 0: rows live in JobResult::row_store
  bool require_emitter = true;       // false: view factors, geometry only (no light needed)
  bool find_indirect = true;  // RunJob fills JobResult::indirect (one more pass over the rows:
                              // 7% of a spilled 200,000-patch Cornell job); a caller that draws
                              // no picture with the direct light per pixel may say false
};

// Checks option values (ranges, hemicube resolution even, ...); INVALID_ARGUMENT names
// the option.
absl::Status ValidateJobOptions(const JobOptions& options);

// The mesh options a job meshes with: faces are grouped (face_grouping.h) only for
// monte_carlo rows of a lit scene (the other methods' rows are per patch, and view factors
// are asked per patch). Inline: the service client meshes with it too, without the solver.
inline MeshOptions JobMeshOptions(const JobOptions& options) {
  MeshOptions mesh = options.mesh;
  mesh.group_faces = mesh.group_faces && options.require_emitter &&
                     options.form_factors.method == FormFactorMethod::kMonteCarlo;
  return mesh;
}

// A job after meshing and the Embree build: everything the row and solve phases need.
// The unknowns (rows, attributes, the solved B) are the patches, or the groups of them in
// `clusters` when faces were grouped; outputs always get one B per patch.
struct PreparedJob {
  Scene scene;
  PatchMesh mesh;
  PatchClusters clusters;  // empty: one unknown per patch
  PatchClusters cells;     // grouped: the direct-light cells (face_grouping.h); else empty
  MeshStats mesh_stats;
  PatchAttributes attributes;  // per unknown
  std::unique_ptr<EmbreeRayCaster> caster;
  // The cells' emitter columns the group rows keep for the push-down (rows.cell_columns).
  CellColumnCache cell_columns;
  RowContext rows;  // points into mesh, caster and cell_columns: PreparedJob is not copyable
                    // or movable
  double load_seconds = 0, mesh_seconds = 0, embree_seconds = 0;

  // The number of unknowns: rows of the system and values the solve computes.
  size_t Unknowns() const { return clusters.empty() ? mesh.size() : clusters.size(); }

  PreparedJob() = default;
  PreparedJob(const PreparedJob&) = delete;
  PreparedJob& operator=(const PreparedJob&) = delete;
};

// Validates the scene and options, subdivides, builds the Embree scene.
absl::StatusOr<std::unique_ptr<PreparedJob>> PrepareJob(Scene scene, const JobOptions& options);
// The same around a mesh meshed already: `mesh` must be SubdivideAndGroup(scene,
// JobMeshOptions(options)) (a server counts a job's unknowns before it starts; the job then
// takes that mesh instead of meshing twice), or any mesh of the scene without groups. Its
// meshing time is booked as the job's.
absl::StatusOr<std::unique_ptr<PreparedJob>> PrepareJob(Scene scene, GroupedMesh mesh,
                                                        const JobOptions& options);

// Upper estimate of a job's peak memory in bytes for n patches (mesh, Embree, rows, solver),
// so a server can refuse before any work starts.
uint64_t EstimateJobBytes(const Scene& scene, const JobOptions& options);
// The same for a scene known to mesh into `patches` patches with options.mesh (counting
// them subdivides the scene: a caller that asks often can count once).
uint64_t EstimateJobBytes(uint64_t patches, const JobOptions& options);

struct JobTimings {
  double load = 0, mesh = 0, embree = 0, rows = 0, solve = 0;  // seconds per phase
  double direct = 0;  // grouped: the cells' direct light and detail after the solve
                      // (cell_direct.h, cell_detail.h)
};

struct JobResult {
  std::unique_ptr<PreparedJob> job;
  CsrMatrix form_factors;               // the rows, unless they are in row_store; an
                                        // adaptive job's are per leaf, not per patch
                                        // (see solved_balance)
  std::unique_ptr<RowStore> row_store;  // options.spill.memory_limit > 0: the rows (some
                                        // may be on disk); form_factors is then empty
  RowBlockStats row_stats;
  SolveResult solve;
  JobTimings timings;
  // Grouped jobs: the solved B per unknown (solve.radiosity is then per patch, with each
  // direct-light cell's own direct light), and what the cells' pass did.
  std::vector<Rgb> unknown_radiosity;
  // Per patch of job->mesh: the radiosity that did not come straight from an emitter
  // (solve/indirect_light.h; a group's patches share their unknown's), for pictures that
  // sample the direct light per pixel. Empty where not known (adaptive, hierarchical) or not
  // asked for (JobOptions::find_indirect).
  std::vector<Rgb> indirect;
  uint64_t direct_cells = 0, direct_kept = 0, direct_rays = 0, direct_lifted = 0;
  uint64_t detail_rays = 0;            // the cells' detail's gather (cell_detail.h)
  uint64_t detail_indirect_cells = 0;  // ... its cells that took their own indirect light
  // Set when the solved unknowns are not job->mesh's patches (adaptive: leaves, each shown
  // by one or more patches): the energy balance of the system that was solved, or why there
  // is none (hierarchical: light moves along links, there are no rows). The report uses it
  // instead of System(), which pairs per-patch attributes with the rows.
  std::optional<absl::StatusOr<EnergyBalance>> solved_balance;
  // What refinement built, for the report: hierarchical's elements and links (memory against
  // n), adaptive meshing's passes.
  std::optional<HierarchicalStats> hierarchical;
  std::vector<AdaptivePass> adaptive_passes;

  // The system the rows and patches form, wherever the rows are.
  RadiositySystem System() const;
  // How the rows of System() were sampled with `options` (the energy balance's noise).
  RowSampling Sampling(const FormFactorOptions& options) const;
  uint64_t RowNonZeros() const;
  uint64_t RowBytes() const;
};

struct JobCallbacks {
  PhaseProgress phase;  // "rows" progress; returning false cancels
  SolveCallback solve;  // per-iteration progress and snapshots
};

// After the solve of a job whose faces were grouped: with direct-light cells, the solve
// continued with the cells' detail as the unknowns see it (cell_detail.h) as a source beside E;
// the balance of the solved (grouped) system into result.solved_balance (the detail's net
// power its cell_detail term), the solved B into result.unknown_radiosity, then
// result.solve.radiosity pushed down to one value per patch: its group's B with its
// direct-light cell's own direct light (PushDownWithCellDirect; the group's area-weighted
// mean stays its B). Nothing to do when the faces were not grouped.
absl::Status PushDownGroupedSolve(const JobOptions& options, JobResult& result);

// result.indirect (JobResult) from the solved unknowns of a job with rows (solve/indirect_light.h),
// pushed down to the patches of a grouped job: after PushDownGroupedSolve. The row store's
// read error when spilled rows cannot be read.
absl::Status FindIndirect(JobResult& result);

// Runs all phases in-process on options.form_factors.threads threads.
absl::StatusOr<JobResult> RunJob(Scene scene, const JobOptions& options,
                                 const JobCallbacks& callbacks = {});

}  // namespace radflux
