#include "solver/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "solver/core/seconds_since.h"
#include "solver/formfactor/cell_detail.h"
#include "solver/formfactor/cell_direct.h"
#include "solver/formfactor/exposed_area.h"
#include "solver/formfactor/reciprocal_columns.h"
#include "solver/formfactor/row_context.h"
#include "solver/hierarchical/hierarchical_job.h"
#include "solver/scene/validation.h"
#include "solver/solve/indirect_light.h"
#include "solver/sparse/file_block_spill.h"

namespace radflux {
namespace {

absl::Status Require(bool ok, const std::string& what) {
  return ok ? absl::OkStatus() : absl::InvalidArgumentError(what);
}

// The job's solver options, on the rows' threads unless --threads says otherwise.
SolverOptions JobSolverOptions(const JobOptions& options) {
  SolverOptions solver = options.solver;
  if (solver.threads == 0) solver.threads = options.form_factors.threads;
  return solver;
}

// The rows of `result`'s job: into result.form_factors, or into a row store that spills
// beyond options.spill.memory_limit.
absl::Status BuildRows(const JobOptions& options, const JobCallbacks& callbacks,
                       JobResult& result) {
  const RowContext& context = result.job->rows;
  if (options.spill.memory_limit == 0) {
    absl::StatusOr<FormFactorResult> rows =
        BuildFormFactors(context, options.form_factors, callbacks.phase);
    if (!rows.ok()) return rows.status();
    result.form_factors = std::move(rows->matrix);
    result.row_stats = rows->stats;
    result.timings.rows = rows->seconds;
    return absl::OkStatus();
  }
  absl::StatusOr<RowBuildSummary> rows = BuildFormFactorsInto(
      context, options.form_factors,
      std::make_unique<RowStore>(static_cast<uint32_t>(result.job->Unknowns()),
                                 options.spill.memory_limit,
                                 std::make_unique<FileBlockSpill>(options.spill.directory)),
      options.spill.directory, callbacks.phase);
  if (!rows.ok()) return rows.status();
  result.row_store = std::move(rows->store);
  result.row_stats = rows->stats;
  result.timings.rows = rows->seconds;
  return absl::OkStatus();
}

}  // namespace

RadiositySystem JobResult::System() const {
  if (row_store != nullptr) return {nullptr, &job->attributes, row_store.get()};
  return {&form_factors, &job->attributes, nullptr};
}

RowSampling JobResult::Sampling(const FormFactorOptions& options) const {
  RowSampling sampling{SampledRays(options), LightSamplesPerRow(options)};
  if (job->rows.mesh != nullptr && job->rows.Unknowns() == job->attributes.size()) {
    sampling.reciprocal = ReciprocallyFilled(job->rows, options);
  }
  return sampling;
}

uint64_t JobResult::RowNonZeros() const {
  return row_store != nullptr ? row_store->nnz() : form_factors.nnz();
}

uint64_t JobResult::RowBytes() const {
  return row_store != nullptr ? row_store->Bytes() : form_factors.Bytes();
}

absl::Status ValidateJobOptions(const JobOptions& o) {
  const FormFactorOptions& f = o.form_factors;
  const SolverOptions& s = o.solver;
  for (const absl::Status& status : {
           Require(o.mesh.target_patches >= 0, "--patches must be >= 0"),
           Require(o.mesh.max_edge >= 0 && std::isfinite(o.mesh.max_edge),
                   "--max-edge must be a finite length >= 0"),
           Require(o.mesh.target_patches == 0 || o.mesh.max_edge == 0,
                   "give --patches or --max-edge, not both"),
           Require(f.rays >= 1 && f.rays <= (1 << 24), "--rays must be in [1, 16777216]"),
           Require(f.hemicube_res >= 2 && f.hemicube_res <= 4096 && f.hemicube_res % 2 == 0,
                   "--hemicube-res must be even and in [2, 4096]"),
           Require(f.samples >= 1 && f.samples <= 65536, "--samples must be in [1, 65536]"),
           Require(f.cutoff >= 0 && f.cutoff < 1, "--cutoff must be in [0, 1)"),
           Require(f.threads >= 0 && f.threads <= 4096, "--threads must be in [0, 4096]"),
           Require(f.block_size >= 1, "block size must be >= 1"),
           Require(s.tolerance > 0 && s.tolerance < 1, "--tolerance must be in (0, 1)"),
           Require(s.max_iterations >= 1, "--max-iterations must be >= 1"),
           Require(o.spill.memory_limit == 0 || StreamsRows(s.method),
                   absl::StrCat("--memory-limit spills rows to disk; solver ",
                                std::string(SolverName(s.method)),
                                " needs them all in memory (use jacobi, gauss_seidel or auto)")),
           Require(o.spill.memory_limit == 0 || (!o.hierarchical.enabled && o.adaptive.passes == 0),
                   "--memory-limit applies to the plain solve, not hierarchical or adaptive"),
           Require(o.hierarchical.link_epsilon > 0 && std::isfinite(o.hierarchical.link_epsilon),
                   "--link-epsilon must be a finite number > 0"),
           Require(o.hierarchical.min_area_fraction > 0 && o.hierarchical.min_area_fraction < 1,
                   "--min-element-area must be in (0, 1)"),
           Require(o.spill.memory_limit > 0 || o.spill.directory.empty(),
                   "--spill-dir needs --memory-limit"),
       }) {
    if (!status.ok()) return status;
  }
  return absl::OkStatus();
}

namespace {

// The scene and options as PrepareJob takes them (ValidateJobOptions, ValidateScene).
absl::Status ValidateJob(const Scene& scene, const JobOptions& options) {
  if (absl::Status s = ValidateJobOptions(options); !s.ok()) return s;
  return ValidateScene(scene, options.require_emitter);
}

// PrepareJob once the scene and options are valid and `mesh` is the scene's.
absl::StatusOr<std::unique_ptr<PreparedJob>> PrepareValidJob(Scene scene, GroupedMesh mesh) {
  auto job = std::make_unique<PreparedJob>();
  job->scene = std::move(scene);
  auto start = std::chrono::steady_clock::now();
  job->mesh = std::move(mesh.mesh);
  job->clusters = std::move(mesh.clusters);
  job->cells = std::move(mesh.cells);
  job->caster = std::move(mesh.caster);
  job->mesh_stats = ComputeMeshStats(job->mesh);
  job->attributes = job->clusters.empty()
                        ? ComputePatchAttributes(job->scene, job->mesh)
                        : ComputeClusterAttributes(job->scene, job->mesh, job->clusters);
  job->mesh_seconds = mesh.seconds - mesh.caster_seconds + SecondsSince(start);

  start = std::chrono::steady_clock::now();
  if (job->caster == nullptr) {  // grouped: built already for the lit probe
    absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> caster = EmbreeRayCaster::Create(job->mesh);
    if (!caster.ok()) return caster.status();
    job->caster = *std::move(caster);
  }
  job->rows = MakeRowContext(job->mesh, job->attributes, *job->caster, &job->clusters, &job->cells);
  if (job->rows.cells != nullptr) {
    job->cell_columns = CellColumnCache(job->cells.size());
    job->rows.cell_columns = &job->cell_columns;
  }
  job->embree_seconds = mesh.caster_seconds + SecondsSince(start);  // grouped: built meshing
  return job;
}

// monte_carlo's rows and the solve's areas of the unknowns' exposed parts (exposed_area.h),
// booked as meshing time; the same on every node that builds the job's rows.
std::unique_ptr<PreparedJob> WithExposedAreas(const JobOptions& options,
                                              std::unique_ptr<PreparedJob> job) {
  const FormFactorOptions& f = options.form_factors;
  if (f.method != FormFactorMethod::kMonteCarlo || !f.exposed_area || options.hierarchical.enabled)
    return job;
  const auto start = std::chrono::steady_clock::now();
  job->rows.exposure = UnknownExposure(job->rows, f.threads);
  for (size_t u = 0; u < job->rows.exposure.size(); ++u) {
    job->attributes.area[u] *= job->rows.exposure[u];
  }
  job->mesh_seconds += SecondsSince(start);
  return job;
}

}  // namespace

absl::StatusOr<std::unique_ptr<PreparedJob>> PrepareJob(Scene scene, const JobOptions& options) {
  if (absl::Status s = ValidateJob(scene, options); !s.ok()) return s;
  absl::StatusOr<GroupedMesh> mesh = SubdivideAndGroup(scene, JobMeshOptions(options));
  if (!mesh.ok()) return mesh.status();
  absl::StatusOr<std::unique_ptr<PreparedJob>> job =
      PrepareValidJob(std::move(scene), *std::move(mesh));
  if (!job.ok()) return job.status();
  return WithExposedAreas(options, *std::move(job));
}

absl::StatusOr<std::unique_ptr<PreparedJob>> PrepareJob(Scene scene, GroupedMesh mesh,
                                                        const JobOptions& options) {
  if (absl::Status s = ValidateJob(scene, options); !s.ok()) return s;
  absl::StatusOr<std::unique_ptr<PreparedJob>> job =
      PrepareValidJob(std::move(scene), std::move(mesh));
  if (!job.ok()) return job.status();
  return WithExposedAreas(options, *std::move(job));
}

uint64_t EstimateJobBytes(const Scene& scene, const JobOptions& options) {
  absl::StatusOr<GroupedMesh> mesh = SubdivideAndGroup(scene, JobMeshOptions(options));
  if (!mesh.ok()) return EstimateJobBytes(0, options);
  const uint64_t patches = mesh->mesh.size();
  const uint64_t unknowns = mesh->clusters.empty() ? patches : mesh->clusters.size();
  // Rows and solver per unknown; the patches beyond them cost their mesh and Embree bytes.
  return EstimateJobBytes(unknowns, options) +
         (patches - unknowns) * (sizeof(Patch) + 4 * sizeof(Vec3) + 2 * sizeof(uint32_t) + 128);
}

uint64_t EstimateJobBytes(uint64_t n, const JobOptions& options) {
  const FormFactorOptions& f = options.form_factors;
  // Non-zeros per row: bounded by n, and by the rays or cells that can land in a row.
  uint64_t per_row = n;
  if (f.method == FormFactorMethod::kMonteCarlo) per_row = std::min<uint64_t>(n, f.rays + 64);
  if (f.method == FormFactorMethod::kHemicube) {
    per_row = std::min<uint64_t>(n, 3ull * f.hemicube_res * f.hemicube_res);
  }
  uint64_t rows = n * per_row * (sizeof(uint32_t) + sizeof(float)) * 2;  // rows + CG copy
  if (options.spill.memory_limit > 0) {  // no CG copy; beyond the budget, chunks in flight
    // and the reciprocity averaging's two (FinishRows)
    const bool averaged = f.method == FormFactorMethod::kMonteCarlo && f.reciprocal_pairs;
    const uint64_t chunks = kRowReadAhead + (averaged ? 4 : 2);
    rows = std::min(rows / 2, options.spill.memory_limit + chunks * kRowChunkBytes);
  }
  const uint64_t mesh_bytes = n * (sizeof(Patch) + 4 * sizeof(Vec3) + 2 * sizeof(Rgb) + 64);
  const uint64_t embree = n * 128;
  const uint64_t solver = n * sizeof(Rgb) * 8;
  const uint64_t direct = options.solver.method == SolverMethod::kDirect ? n * n * 8 : 0;
  return rows + mesh_bytes + embree + solver + direct;
}

absl::Status FindIndirect(JobResult& result) {
  const bool grouped = !result.job->clusters.empty();
  absl::StatusOr<std::vector<Rgb>> indirect = ReflectedIndirect(
      result.System(), grouped ? result.unknown_radiosity : result.solve.radiosity);
  if (!indirect.ok()) return indirect.status();
  result.indirect =
      grouped ? PushDownToPatches(result.job->clusters, *indirect) : *std::move(indirect);
  return absl::OkStatus();
}

absl::StatusOr<JobResult> RunJob(Scene scene, const JobOptions& options,
                                 const JobCallbacks& callbacks) {
  if (options.hierarchical.enabled) return RunHierarchicalJob(std::move(scene), options, callbacks);
  if (options.adaptive.passes > 0) return RunAdaptiveJob(std::move(scene), options, callbacks);
  JobResult result;
  absl::StatusOr<std::unique_ptr<PreparedJob>> job = PrepareJob(std::move(scene), options);
  if (!job.ok()) return job.status();
  result.job = *std::move(job);
  result.timings.mesh = result.job->mesh_seconds;
  result.timings.embree = result.job->embree_seconds;

  if (absl::Status s = BuildRows(options, callbacks, result); !s.ok()) return s;

  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<SolveResult> solved =
      Solve(result.System(), JobSolverOptions(options), callbacks.solve);
  if (!solved.ok()) return solved.status();
  result.solve = *std::move(solved);
  result.timings.solve = SecondsSince(start);
  if (absl::Status s = PushDownGroupedSolve(options, result); !s.ok()) return s;
  if (options.find_indirect) {
    if (absl::Status s = FindIndirect(result); !s.ok()) return s;
  }
  return result;
}

namespace {

// The first solve's iterations and history ahead of the continued solve's.
void PrependSolve(const SolveResult& first, SolveResult& then) {
  then.iterations += first.iterations;
  then.residual_history.insert(then.residual_history.begin(), first.residual_history.begin(),
                               first.residual_history.end());
  then.requested = first.requested;
  then.method = first.method;
  std::vector<SolverMethod> used = first.methods_used;
  for (SolverMethod m : then.methods_used) {
    if (used.empty() || used.back() != m) used.push_back(m);
  }
  then.methods_used = std::move(used);
  if (then.fallback_reason.empty()) then.fallback_reason = first.fallback_reason;
}

// A grouped job with direct-light cells: the cells' detail as the unknowns with rows see it
// (GatherCellDetail, from the solved B: the emitters' for the direct light, every unknown's
// for the cells' own indirect light), rho H added to the source, and the solve
// continued from its B with the method that finished it: result.solve then solves
// B = E + rho (H + F B). Returns the detail: H per unknown and the cells' indirect deviation
// (both empty without cells, or when the solve was cancelled or did not converge: it is then
// left as it stopped, and says so).
absl::StatusOr<CellDetail> SolveWithCellDetail(const JobOptions& options, JobResult& result) {
  if (result.job->rows.cells == nullptr || result.solve.cancelled || !result.solve.converged) {
    return CellDetail{};
  }
  const auto start = std::chrono::steady_clock::now();
  PatchAttributes source = result.job->attributes;
  const CellDirectLight light =
      ComputeCellDirectLight(result.job->rows, result.solve.radiosity, options.form_factors);
  const SolvedLight light_so_far{result.solve.radiosity, source.reflectance};
  CellDetail detail = GatherCellDetail(result.job->rows, CellDeviation(light, source),
                                       options.form_factors, &light_so_far);
  for (uint32_t u = 0; u < source.size(); ++u) {
    for (int b = 0; b < kBands; ++b) {
      source.emission[u][b] += source.reflectance[u][b] * detail.irradiance[u][b];
    }
  }
  result.detail_rays = detail.rays;
  result.detail_indirect_cells = detail.indirect_cells;
  result.direct_kept = light.kept;  // the push-down finds every cell kept after this pass
  result.direct_rays = light.rays;
  result.timings.direct += SecondsSince(start);

  const auto solve_start = std::chrono::steady_clock::now();
  SolverOptions solver_options = JobSolverOptions(options);
  if (!result.solve.methods_used.empty()) solver_options.method = result.solve.methods_used.back();
  const std::vector<Rgb> first = std::move(result.solve.radiosity);
  solver_options.initial = &first;
  RadiositySystem system = result.System();
  system.patches = &source;
  absl::StatusOr<SolveResult> solved = Solve(system, solver_options);
  if (!solved.ok()) return solved.status();
  PrependSolve(result.solve, *solved);
  result.solve = *std::move(solved);
  result.timings.solve += SecondsSince(solve_start);
  return detail;
}

}  // namespace

absl::Status PushDownGroupedSolve(const JobOptions& options, JobResult& result) {
  const PatchClusters& clusters = result.job->clusters;
  if (clusters.empty()) return absl::OkStatus();
  absl::StatusOr<CellDetail> detail = SolveWithCellDetail(options, result);
  if (!detail.ok()) return detail.status();
  absl::StatusOr<EnergyBalance> balance = StreamEnergyBalance(
      result.System(), result.solve.radiosity, result.Sampling(options.form_factors),
      result.row_stats.scaled_off, detail->irradiance);
  if (!balance.ok()) return balance.status();
  result.solved_balance = *balance;
  result.unknown_radiosity = result.solve.radiosity;
  CellDirectResult pushed =
      PushDownWithCellDirect(result.job->rows, result.job->attributes, result.unknown_radiosity,
                             options.form_factors, detail->indirect);
  result.solve.radiosity = std::move(pushed.radiosity);
  result.direct_cells = pushed.cells;
  if (detail->irradiance.empty()) result.direct_kept = pushed.kept;
  result.direct_rays += pushed.rays;
  result.direct_lifted = pushed.lifted;
  result.timings.direct += pushed.seconds;
  return absl::OkStatus();
}

}  // namespace radflux
