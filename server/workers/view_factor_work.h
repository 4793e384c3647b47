// A view-factor job's rows as the row farm shares them (issue 23): blocks of SurfaceRowPlan's
// rows, built alike by the server's threads and by worker nodes. A worker reads the job's
// model as the server does (PrepareViewFactorRun) and builds the plan the server chose: the
// lease's options pin it (ViewFactorLeaseOptions), whatever the worker's memory.
#pragma once

#include <cstdint>
#include <memory>

#include "absl/status/statusor.h"
#include "radflux/v1/worker.pb.h"
#include "server/store/stored_codec.h"
#include "solver/formfactor/surface_rows.h"
#include "solver/formfactor/view_factor_job.h"
#include "wire/stored_scene.h"

namespace radflux {

// A view-factor job's surfaces and its plan of rows (which references them: not movable).
struct ViewFactorWork {
  FaceSurfaces surfaces;
  std::unique_ptr<SurfaceRowPlan> plan;
  SurfaceRowsStats stats;  // the plan's (blockers, budget, reciprocal)
};

// Rows per block of a view-factor job of `surfaces` rows: 64, fewer when that would pass
// 2 MiB of values (a block's result stays far below a worker message's limit).
uint32_t ViewFactorBlockRows(size_t surfaces);

// The job's work from its request options (`options.job`-style SolveOptions with
// viewfactors set) and its stored scene: FAILED_PRECONDITION unless it integrates per
// surface pair (only such jobs are shared); `threads` for each block built.
absl::StatusOr<std::unique_ptr<ViewFactorWork>> PrepareViewFactorWork(
    const v1::SolveOptions& options, StoredScene stored, int threads);

// Rows [first, first + count) of the plan as a row block (StoredRowBlock::view_factors).
StoredRowBlock BuildViewFactorBlock(const SurfaceRowPlan& plan, uint32_t first, uint32_t count);

// The options leased to workers for a job of `options` whose plan is `plan`: memory_limit
// set so that a worker's plan is reciprocal exactly when the server's is.
v1::SolveOptions ViewFactorLeaseOptions(v1::SolveOptions options, const SurfaceRowPlan& plan);

}  // namespace radflux
