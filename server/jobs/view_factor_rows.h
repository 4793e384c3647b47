// A view-factor job's adaptive rows in the service (issue 23): SurfaceRowPlan's blocks of
// ViewFactorBlockRows rows, shared through the row farm like form-factor row blocks. Blocks
// stored in the job's directory (a resumed job's) are reused; the others are built by the
// server's threads and by worker nodes, whose blocks are checked (CheckDenseBlock: every
// value, and a sample of rows recomputed here bit for bit); each block is stored as it
// arrives (store/view_factor_blocks.h), and once all are, the rows go to the sink in order.
// Rows do not depend on who built them: the output is the same with 0 or N workers.
#pragma once

#include <cstddef>

#include "radflux/v1/job.pb.h"
#include "server/jobs/job_runner.h"
#include "server/workers/row_farm.h"
#include "solver/formfactor/view_factor_job.h"

namespace radflux {

// What the rows' phase did, for the job's report.
struct ViewFactorRowsReport {
  size_t reused_rows = 0;  // rows of blocks stored before (a resumed job)
  FarmReport farm;         // rows from workers, verified, rejected
};

// The SurfaceRowsBuilder (view_factor_job.h) of `job` run with `context` (its store, farm,
// threads, stop flag and failure callback); fills `report`. A failed write of a block fails
// the job (context.fail); a stop returns CANCELLED (stored blocks kept for the resume).
SurfaceRowsBuilder FarmedViewFactorRows(const v1::Job& job, const RunContext& context,
                                        ViewFactorRowsReport& report);

}  // namespace radflux
