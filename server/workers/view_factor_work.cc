#include "server/workers/view_factor_work.h"

#include <algorithm>

#include "server/jobs/view_factor_runner.h"

namespace radflux {

uint32_t ViewFactorBlockRows(size_t surfaces) {
  constexpr size_t kBlockValues = size_t{1} << 18;  // 2 MiB of doubles
  return static_cast<uint32_t>(std::clamp<size_t>(kBlockValues / std::max<size_t>(surfaces, 1), 1, 64));
}

absl::StatusOr<std::unique_ptr<ViewFactorWork>> PrepareViewFactorWork(
    const v1::SolveOptions& options, StoredScene stored, int threads) {
  absl::StatusOr<ViewFactorRun> run = PrepareViewFactorRun(options, std::move(stored));
  if (!run.ok()) return run.status();
  std::optional<FaceSurfaces> surfaces = SurfacesOfOneFace(run->model.scene, run->options.by);
  if (run->options.integration != ViewFactorIntegration::kAdaptive || !surfaces) {
    return absl::FailedPreconditionError(
        "only view-factor jobs integrated per surface pair are built by workers");
  }
  auto work = std::make_unique<ViewFactorWork>();
  work->surfaces = *std::move(surfaces);
  SurfaceRowsOptions rows = run->options.surface_rows;
  rows.threads = threads;
  work->plan = std::make_unique<SurfaceRowPlan>(work->surfaces.shapes, work->surfaces.radiating,
                                                rows, work->stats);
  return work;
}

StoredRowBlock BuildViewFactorBlock(const SurfaceRowPlan& plan, uint32_t first, uint32_t count) {
  StoredRowBlock block;
  block.view_factors = true;
  block.block.first_row = first;
  block.block.row_begin.assign(count + 1, 0);
  block.values.resize(plan.BlockValues(first, count));
  SurfaceRowsStats stats;
  plan.BuildBlock(first, count, block.values, stats);
  return block;
}

v1::SolveOptions ViewFactorLeaseOptions(v1::SolveOptions options, const SurfaceRowPlan& plan) {
  const uint64_t triangle = TriangleBytes(plan.radiating());
  options.mutable_viewfactors()->set_memory_limit(
      plan.reciprocal() ? triangle : std::max<uint64_t>(triangle, 2) - 1);
  return options;
}

}  // namespace radflux
