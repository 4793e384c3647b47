// RunStoredJob: the phases of one job as the server runs them: prepare, form-factor rows
// block by block (checkpointed in groups, stored blocks reused), then the solve
// (checkpointed). A job resumed after a crash computes exactly what an uninterrupted run
// computes: rows are deterministic per patch; the solve resumes from its checkpoint bit for
// bit for jacobi, gauss_seidel (B) and southwell (B and the unshot radiosity), and cg warm
// starts from the checkpointed B (same answer within the tolerance); direct restarts.
// A job whose rows do not fit context.max_memory keeps them in a RowStore that spills to a
// file in its job directory (rebuilt from the stored rows on resume).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "absl/status/statusor.h"
#include "nlohmann/json.hpp"
#include "radflux/v1/job.pb.h"
#include "server/jobs/job_hub.h"
#include "server/jobs/scene_cache.h"
#include "server/store/job_store.h"
#include "server/store/result_codec.h"

namespace radflux {

class RowFarm;
struct FarmReport;

struct RunContext {
  JobStore* store = nullptr;
  SceneCache* scenes = nullptr;                  // the job's scene comes from here
  JobHub* hub = nullptr;                         // receives progress events and snapshots
  const std::atomic<bool>* stop = nullptr;       // cancel or shutdown: stop at the next safe point
  const std::atomic<bool>* cancelled = nullptr;  // set (before stop) when stopping for a cancel
  int threads = 0;                               // OpenMP threads for this job (0 = all cores)
  double checkpoint_seconds = 1.0;  // at most one row-block and one solver checkpoint per interval
  int solve_delay_ms = 0;           // testing: sleep after each solver iteration
  int snapshot_interval_ms = 100;   // at most one snapshot per this interval reaches the hub
  RowFarm* farm = nullptr;  // shares the row blocks with worker nodes (null: this job's own)
  int block_delay_ms = 0;   // testing: sleep after each row block built here
  // Bytes per job (EstimateJobBytes); a job whose rows do not fit spills them to a file in
  // its directory of the store (see row_budget.h).
  uint64_t max_memory = UINT64_MAX;
  // Called when the job enters a phase (patches = 0 until meshed).
  std::function<void(v1::Phase phase, int64_t patches)> on_phase;
  // Called when a write of the job's files fails (a full disk): the job is to end FAILED
  // with that error; the callee sets *stop, so the job stops at its next safe point.
  std::function<void(const absl::Status& error)> fail;
};

// The report's "workers" section: rows from workers, how many were verified here and at
// what cost, and every block rejected (with its worker and why).
nlohmann::json WorkersJson(const FarmReport& report);

// Runs the job to completion and returns its encoded result and its blob file (see
// result_codec.h); CANCELLED when *stop was set (rows done so far and a checkpoint stay
// stored).
absl::StatusOr<EncodedResult> RunStoredJob(const v1::Job& job, const RunContext& context);

}  // namespace radflux
