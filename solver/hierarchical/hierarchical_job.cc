#include "solver/hierarchical/hierarchical_job.h"

#include <chrono>

#include "solver/core/seconds_since.h"
#include "solver/scene/validation.h"
#include "solver/solve/energy_balance.h"

namespace radflux {
namespace {

// A PreparedJob around an already built output mesh (one unknown per patch).
absl::StatusOr<std::unique_ptr<PreparedJob>> PrepareFromMesh(Scene scene, PatchMesh mesh,
                                                             const JobOptions& options) {
  GroupedMesh ungrouped;
  ungrouped.mesh = std::move(mesh);
  return PrepareJob(std::move(scene), std::move(ungrouped), options);
}

absl::Status Validate(const Scene& scene, const JobOptions& options) {
  if (absl::Status s = ValidateJobOptions(options); !s.ok()) return s;
  return ValidateScene(scene);
}

SolverOptions WithThreads(const JobOptions& options) {
  SolverOptions s = options.solver;
  if (s.threads == 0) s.threads = options.form_factors.threads;
  return s;
}

}  // namespace

absl::StatusOr<JobResult> RunHierarchicalJob(Scene scene, const JobOptions& options,
                                             const JobCallbacks& callbacks) {
  if (absl::Status s = Validate(scene, options); !s.ok()) return s;
  HierarchicalOptions h = options.hierarchical;
  h.samples = options.form_factors.samples;
  h.seed = options.form_factors.seed;
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<HierarchicalResult> solved =
      SolveHierarchical(scene, h, WithThreads(options), callbacks.solve);
  if (!solved.ok()) return solved.status();
  const double seconds = SecondsSince(start);
  const HierarchicalStats& st = solved->stats;
  JobResult result;
  absl::StatusOr<std::unique_ptr<PreparedJob>> job =
      PrepareFromMesh(std::move(scene), std::move(solved->mesh), options);
  if (!job.ok()) return job.status();
  result.job = *std::move(job);
  const uint32_t n = static_cast<uint32_t>(result.job->mesh.size());
  result.form_factors.rows = result.form_factors.cols = n;
  result.form_factors.row_begin.assign(n + 1, 0);
  result.row_stats.rays = st.rays;
  result.hierarchical = st;
  result.solved_balance = absl::UnimplementedError(
      "not computed for --solver hierarchical: light moves along links, there are no rows");
  result.solve = std::move(solved->solve);
  result.timings.rows = st.refine_seconds;
  result.timings.solve = st.solve_seconds;
  result.timings.mesh = seconds - st.refine_seconds - st.solve_seconds;
  return result;
}

absl::StatusOr<JobResult> RunAdaptiveJob(Scene scene, const JobOptions& options,
                                         const JobCallbacks& callbacks) {
  if (absl::Status s = Validate(scene, options); !s.ok()) return s;
  absl::StatusOr<AdaptiveResult> solved =
      SolveAdaptive(scene, options.mesh, options.form_factors, WithThreads(options),
                    options.adaptive, callbacks.solve);
  if (!solved.ok()) return solved.status();
  double rows_seconds = 0;
  for (size_t k = 0; k < solved->passes.size(); ++k) {
    const AdaptivePass& p = solved->passes[k];
    rows_seconds += p.seconds;
  }
  // The rows stay per leaf (a leaf is shown by one or more patches of the conforming mesh;
  // expanding rows to those patches multiplied the entries ~20x); the balance is the leaf
  // system's.
  AdaptiveResult& a = *solved;
  const PatchMesh& display = a.mesh;
  const PatchAttributes leaf_attributes = ComputePatchAttributes(scene, a.leaf_mesh);
  const EnergyBalance balance = ComputeEnergyBalance(
      {&a.form_factors, &leaf_attributes, nullptr}, a.leaf_radiosity,
      {SampledRays(options.form_factors), LightSamplesPerRow(options.form_factors)});
  JobResult result;
  absl::StatusOr<std::unique_ptr<PreparedJob>> job =
      PrepareFromMesh(std::move(scene), display, options);
  if (!job.ok()) return job.status();
  result.job = *std::move(job);
  result.form_factors = std::move(a.form_factors);
  result.solved_balance = balance;
  result.adaptive_passes = a.passes;
  result.row_stats.rays = a.rays;
  result.solve = a.solve;
  result.solve.radiosity.resize(display.size());
  for (uint32_t p = 0; p < display.size(); ++p)
    result.solve.radiosity[p] = a.leaf_radiosity[a.patch_leaf[p]];
  result.timings.rows = rows_seconds;
  return result;
}

}  // namespace radflux
