#include "server/jobs/view_factor_rows.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>

#include "server/store/view_factor_blocks.h"
#include "server/workers/view_factor_work.h"

namespace radflux {
namespace {

using Clock = std::chrono::steady_clock;

// Whether a stored block belongs to `plan` and holds the rows its name says.
bool Fits(const ViewFactorBlock& b, const SurfaceRowPlan& plan, size_t block_rows) {
  const size_t n = plan.radiating();
  return b.surfaces == n && b.reciprocal == plan.reciprocal() && b.first % block_rows == 0 &&
         b.first < n && b.count == std::min(block_rows, n - b.first) &&
         b.values.size() == plan.BlockValues(b.first, b.count);
}

// The blocks not stored in `dir` for `plan` (stored ones are read and checked; those that
// do not fit are logged and built again); the rows of the others in *reused.
std::vector<uint32_t> MissingBlocks(const std::string& dir, const SurfaceRowPlan& plan,
                                    size_t block_rows, const std::string& job_id, size_t* reused) {
  std::set<uint64_t> stored;
  for (uint64_t first : StoredViewFactorBlocks(dir)) {
    absl::StatusOr<ViewFactorBlock> block = GetViewFactorBlock(dir, first);
    if (block.ok() && Fits(*block, plan, block_rows)) {
      stored.insert(first);
      *reused += block->count;
    } else {
      spdlog::warn("job {}: stored view-factor rows from {} not reused ({})", job_id, first,
                   block.ok() ? "another plan of rows" : std::string(block.status().message()));
    }
  }
  std::vector<uint32_t> missing;
  for (size_t first = 0, b = 0; first < plan.radiating(); first += block_rows, ++b) {
    if (!stored.contains(first)) missing.push_back(static_cast<uint32_t>(b));
  }
  return missing;
}

// The server's own values of one row, to check workers' blocks against.
DenseRows PlanRows(const SurfaceRowPlan& plan) {
  return DenseRows{
      [&plan](uint32_t first, uint32_t count) { return plan.BlockValues(first, count); },
      [&plan](uint32_t row) {
        std::vector<double> values(plan.RowWidth(row));
        SurfaceRowsStats stats;
        plan.BuildBlock(row, 1, values, stats);
        return values;
      }};
}

// Builds the missing blocks here and by the farm's workers, each stored by `store`.
void BuildBlocks(const SurfaceRowPlan& plan, const FarmJob& spec,
                 const std::vector<uint32_t>& missing, const RowFarm::BlockSink& store,
                 RowFarm& farm, const RunContext& c) {
  farm.Open(spec, missing, store);
  while (const std::optional<uint32_t> b = farm.NextLocal(spec.job_id, c.stop)) {
    const uint32_t first = *b * spec.block_size;
    const uint32_t count = std::min(spec.block_size, spec.patch_count - first);
    StoredRowBlock rows = BuildViewFactorBlock(plan, first, count);
    if (c.block_delay_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(c.block_delay_ms));
    if (!farm.ClaimLocal(spec.job_id, *b)) continue;  // a worker delivered it first
    store(*b, std::move(rows));
    farm.FinishBlock(spec.job_id, *b);
  }
}

}  // namespace

SurfaceRowsBuilder FarmedViewFactorRows(const v1::Job& job, const RunContext& c,
                                        ViewFactorRowsReport& report) {
  return [&job, &c, &report](const std::vector<SurfaceShape>& shapes, size_t radiating,
                             const SurfaceRowsOptions& options, const SurfaceRowSink& sink,
                             SurfaceRowsStats& stats) -> absl::Status {
    const std::string dir = c.store->JobDir(job.job_id());
    const SurfaceRowPlan plan(shapes, radiating, options, stats);
    const auto start = Clock::now();
    const uint32_t block_rows = ViewFactorBlockRows(radiating);
    const std::vector<uint32_t> missing =
        MissingBlocks(dir, plan, block_rows, job.job_id(), &report.reused_rows);
    if (report.reused_rows > 0) {
      spdlog::info("job {}: reused {} stored view-factor rows of {}", job.job_id(),
                   report.reused_rows, radiating);
    }
    std::mutex mu;  // guards done and error
    size_t done = report.reused_rows;
    absl::Status error;
    const auto store = [&](uint32_t b, StoredRowBlock rows) {
      const size_t first = size_t{b} * block_rows, count = std::min<size_t>(block_rows, radiating - first);
      const absl::Status s = PutViewFactorBlock(
          dir, ViewFactorBlock{radiating, plan.reciprocal(), first, count, std::move(rows.values)});
      std::lock_guard lock(mu);
      if (!s.ok() && error.ok()) c.fail(error = s);
      done += count;
      if (options.on_rows) options.on_rows(done, radiating);
    };
    RowFarm own_farm;
    RowFarm& farm = c.farm ? *c.farm : own_farm;
    const FarmJob spec{job.job_id(), job.scene_sha256(), ViewFactorLeaseOptions(job.options(), plan),
                       static_cast<uint32_t>(radiating), block_rows, {}, {}, PlanRows(plan)};
    BuildBlocks(plan, spec, missing, store, farm, c);
    const bool all_done = farm.AllDone(job.job_id());
    report.farm = farm.Close(job.job_id());
    if (c.stop && c.stop->load()) return absl::CancelledError("view-factor rows stopped");
    if (!error.ok()) return error;
    if (!all_done) return absl::InternalError("view-factor rows ended with blocks missing");
    absl::Status emitted = plan.Emit(
        block_rows,
        [&](size_t first) -> absl::StatusOr<std::vector<double>> {
          absl::StatusOr<ViewFactorBlock> block = GetViewFactorBlock(dir, first);
          if (!block.ok()) return block.status();
          return std::move(block->values);
        },
        sink);
    stats.rows_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return emitted;
  };
}

}  // namespace radflux
