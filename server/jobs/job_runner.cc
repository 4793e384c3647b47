#include "server/jobs/job_runner.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <future>
#include <optional>
#include <thread>

#include "absl/strings/str_format.h"
#include "server/jobs/progress_throttle.h"
#include "server/jobs/row_budget.h"
#include "server/jobs/view_factor_runner.h"
#include "server/store/result_codec.h"
#include "server/store/row_block_writer.h"
#include "server/store/row_sink.h"
#include "server/workers/row_check.h"
#include "server/workers/row_farm.h"
#include "solver/core/parallel.h"
#include "solver/core/seconds_since.h"
#include "solver/pipeline.h"
#include "solver/report.h"
#include "solver/sparse/file_block_spill.h"
#include "wire/proto_convert.h"

namespace radflux {
namespace {

using Clock = std::chrono::steady_clock;

bool Stopped(const RunContext& c) { return c.stop && c.stop->load(); }

// Watchers get at most one progress event per round of the hub's writes (the newest): four
// a second for a progress bar.
constexpr auto kProgressInterval = JobHub::kWakeInterval;

// Publishes a progress event of the running job (throttled).
void PublishProgress(ProgressThrottle& throttle, v1::Phase phase, const v1::Progress& progress) {
  v1::JobEvent event;
  event.set_state(v1::JOB_STATE_RUNNING);
  event.set_phase(phase);
  *event.mutable_progress() = progress;
  throttle.Publish(std::move(event));
}

// The job's rows, in memory, or in a RowStore keeping `row_budget` bytes (> 0) in memory
// and spilling the rest to a file in the job's directory.
RowSink MakeRowSink(const v1::Job& job, uint32_t n, uint32_t block_count, uint64_t row_budget,
                    const RunContext& c) {
  if (row_budget == 0) return RowSink(n, block_count, nullptr);
  return RowSink(
      n, block_count,
      std::make_unique<RowStore>(n, row_budget,
                                 std::make_unique<FileBlockSpill>(c.store->JobDir(job.job_id()))));
}

// All row blocks of the job: stored ones are read back (and rebuilt when malformed), missing
// ones built (in parallel, here and by workers, whose blocks are verified) and handed to
// `writer` as each completes; all go to the sink. What the workers did in *farm_report.
absl::StatusOr<JobRows> BuildStoredRows(const v1::Job& job, const PreparedJob& prepared,
                                        const FormFactorOptions& options, uint64_t row_budget,
                                        const RunContext& c, RowBlockWriter& writer,
                                        ProgressThrottle& throttle, FarmReport* farm_report) {
  const auto start = Clock::now();
  const uint32_t n = static_cast<uint32_t>(prepared.Unknowns());
  const uint32_t block_size = static_cast<uint32_t>(std::max(1, options.block_size));
  const uint32_t block_count = (n + block_size - 1) / block_size;
  RowSink sink = MakeRowSink(job, n, block_count, row_budget, c);
  absl::Status sink_error;  // the first failure to append (guarded by mu below)
  int64_t done = 0;
  std::vector<absl::Status> unreadable;
  c.store->ForEachRowBlock(
      job.job_id(),
      [&](StoredRowBlock stored) {
        const uint32_t b = stored.block.first_row / block_size;
        if (b >= block_count || stored.block.first_row != b * block_size || sink.Has(b)) return;
        const uint32_t count = std::min(block_size, n - stored.block.first_row);
        if (absl::StatusOr<std::vector<uint32_t>> shape =
                CheckRowBlock(stored.block, stored.block.first_row, count, n);
            !shape.ok()) {
          unreadable.push_back(shape.status());
          return;
        }
        done += stored.block.RowCount();
        if (absl::Status s = sink.Put(b, std::make_shared<const StoredRowBlock>(std::move(stored)));
            !s.ok() && sink_error.ok()) {
          sink_error = s;
        }
      },
      &unreadable);
  for (const absl::Status& s : unreadable) {
    spdlog::warn("job {}: stored rows unreadable ({}), rebuilding them", job.job_id(),
                 std::string(s.message()));
  }
  std::vector<uint32_t> missing;
  for (uint32_t b = 0; b < block_count; ++b) {
    if (!sink.Has(b)) missing.push_back(b);
  }
  if (done > 0) spdlog::info("job {}: reusing {} stored rows of {}", job.job_id(), done, n);
  const std::unique_ptr<RowBuilder> builder = MakeRowBuilder(prepared.rows, options);
  const int threads = ThreadCount(c.threads);
  std::vector<std::unique_ptr<RowAccumulator>> scratch(static_cast<size_t>(threads));
  std::mutex mu;  // guards done, rays, sink_error and event publishing order
  uint64_t rays = 0;
  // Every block built (here or by a worker) goes to the store, the sink and the progress
  // events.
  const auto store_block = [&](uint32_t b, StoredRowBlock s) {
    const int64_t count = s.block.RowCount();
    const uint64_t block_rays = s.stats.rays;
    auto shared = std::make_shared<const StoredRowBlock>(std::move(s));
    writer.Put(shared);
    absl::Status put = sink.Put(b, std::move(shared));
    std::lock_guard lock(mu);
    if (!put.ok() && sink_error.ok()) sink_error = put;
    done += count;
    rays += block_rays;
    v1::Progress progress;
    progress.set_rows_done(done);
    progress.set_rows_total(n);
    const double seconds = SecondsSince(start);
    if (seconds > 0) progress.set_rays_per_second(static_cast<double>(rays) / seconds);
    progress.set_eta_seconds(seconds / static_cast<double>(done) * static_cast<double>(n - done));
    PublishProgress(throttle, v1::PHASE_ROWS, progress);
  };
  // The missing blocks are shared with the worker nodes (if any) through the row farm;
  // the server's own threads take blocks from it too, so a job finishes without workers.
  RowFarm own_farm;
  RowFarm& farm = c.farm ? *c.farm : own_farm;
  // Workers' rows are checked against this server's own, row by row (one scratch each).
  const RowRebuilder rebuild = [&](uint32_t first, uint32_t count) {
    RowAccumulator row(n);
    RowBlockStats stats;
    return BuildRowBlock(*builder, prepared.rows, options.cutoff, first, count, row, stats);
  };
  const auto max_row_sum = [&](uint32_t row) { return prepared.rows.MaxRowSum(row); };
  farm.Open(FarmJob{job.job_id(), job.scene_sha256(), job.options(), n, block_size, rebuild,
                    max_row_sum, std::nullopt},
            missing, store_block);
  ParallelFor(threads, 1, threads, [&](int64_t, int64_t) {
    auto& row = scratch[static_cast<size_t>(ThreadIndex())];
    if (!row) row = std::make_unique<RowAccumulator>(n);
    while (const std::optional<uint32_t> b = farm.NextLocal(job.job_id(), c.stop)) {
      const uint32_t first = *b * block_size;
      const uint32_t count = std::min(block_size, n - first);
      StoredRowBlock s;
      s.block = BuildRowBlock(*builder, prepared.rows, options.cutoff, first, count, *row, s.stats);
      if (c.block_delay_ms > 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(c.block_delay_ms));
      }
      if (!farm.ClaimLocal(job.job_id(), *b)) continue;  // a worker delivered it first
      store_block(*b, std::move(s));
      farm.FinishBlock(job.job_id(), *b);
    }
  });
  const bool all_done = farm.AllDone(job.job_id());
  *farm_report = farm.Close(job.job_id());
  if (!all_done && !Stopped(c)) return absl::InternalError("row phase ended with blocks missing");
  if (Stopped(c)) return absl::CancelledError("stopped during form-factor rows");
  if (!sink_error.ok()) return sink_error;
  // Stored, built here and by workers alike, the rows take the builder's pass once all are in.
  absl::StatusOr<JobRows> rows = sink.Finish();
  if (!rows.ok()) return rows;
  if (rows->store == nullptr) {
    FinishRows(*builder, threads, rows->matrix);
  } else {
    absl::StatusOr<std::unique_ptr<RowStore>> finished =
        FinishRows(*builder, threads, std::move(rows->store), c.store->JobDir(job.job_id()));
    if (!finished.ok()) return finished.status();
    rows->store = *std::move(finished);
  }
  rows->seconds = SecondsSince(start);
  return rows;
}

// Every iterative method resumes from a checkpoint: jacobi and gauss_seidel from B
// (their next iterate depends on B alone: bit-identical), southwell from B and its unshot
// radiosity (bit-identical), cg warm-started from B (it restarts its Krylov space, so the
// result agrees within the tolerance, not bit for bit). direct restarts its solve.
bool ResumableSolver(SolverMethod method) { return method != SolverMethod::kDirect; }

// The checkpoint to resume from, if the job has a usable one for this method.
std::optional<SolverCheckpoint> UsableCheckpoint(const v1::Job& job, SolverMethod method, size_t n,
                                                 const RunContext& c) {
  if (!ResumableSolver(method)) return std::nullopt;
  absl::StatusOr<SolverCheckpoint> checkpoint = c.store->GetCheckpoint(job.job_id());
  const size_t unshot = method == SolverMethod::kSouthwell ? n : 0;
  if (!checkpoint.ok() || checkpoint->radiosity.size() != n ||
      checkpoint->method != static_cast<int32_t>(method) || checkpoint->unshot.size() != unshot) {
    return std::nullopt;
  }
  return *std::move(checkpoint);
}

// The solve phase: resumes from the job's checkpoint when there is a usable one, publishes
// progress and snapshots every iteration (throttled), checkpoints every
// context.checkpoint_seconds.
absl::StatusOr<SolveResult> SolveStored(const v1::Job& job, const PreparedJob& p,
                                        const JobRows& rows, SolverOptions so, const RunContext& c,
                                        ProgressThrottle& throttle) {
  const int64_t n = static_cast<int64_t>(p.Unknowns());
  so.threads = c.threads;
  so.cancel = c.stop;
  so.snapshot_every = 1;
  const std::optional<SolverCheckpoint> checkpoint =
      UsableCheckpoint(job, so.method, static_cast<size_t>(n), c);
  const int offset = checkpoint ? checkpoint->iteration : 0;
  if (checkpoint) {
    so.initial = &checkpoint->radiosity;
    if (!checkpoint->unshot.empty()) so.initial_unshot = &checkpoint->unshot;
    so.max_iterations = std::max(0, so.max_iterations - offset);
    spdlog::info("job {}: resuming the solve at iteration {}", job.job_id(), offset);
  }
  SolverCheckpoint last;
  last.method = static_cast<int32_t>(so.method);
  auto last_checkpoint = Clock::now();
  const auto on_progress = [&](const SolveProgress& sp) {
    v1::Progress progress;
    progress.set_rows_done(n);
    progress.set_rows_total(n);
    progress.set_iteration(offset + sp.iteration);
    progress.set_residual(sp.residual);
    progress.set_unshot_fraction(sp.unshot_fraction);
    PublishProgress(throttle, v1::PHASE_SOLVE, progress);
    if (c.solve_delay_ms > 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(c.solve_delay_ms));
    }
    if (!sp.snapshot) return;
    throttle.PublishSnapshot(
        {offset + sp.iteration,
         std::make_shared<const std::vector<Rgb>>(
             p.clusters.empty() ? *sp.snapshot : PushDownToPatches(p.clusters, *sp.snapshot))});
    if (!ResumableSolver(so.method) || sp.state == nullptr) return;
    last.iteration = offset + sp.iteration;
    last.radiosity = *sp.state;
    if (sp.state_unshot != nullptr) last.unshot = *sp.state_unshot;
    if (SecondsSince(last_checkpoint) >= c.checkpoint_seconds) {
      if (absl::Status s = c.store->PutCheckpoint(job.job_id(), last); !s.ok()) {
        spdlog::warn("job {}: checkpoint failed: {}", job.job_id(), std::string(s.message()));
        c.fail(s);
      }
      last_checkpoint = Clock::now();
    }
  };
  throttle.RestartSnapshotInterval();
  absl::StatusOr<SolveResult> solved =
      Solve(RadiositySystem{rows.store ? nullptr : &rows.matrix, &p.attributes, rows.store.get()},
            so, on_progress);
  if (!solved.ok()) return solved.status();
  if (solved->cancelled || Stopped(c)) {
    if (!last.radiosity.empty()) (void)c.store->PutCheckpoint(job.job_id(), last);
    return absl::CancelledError("stopped during the solve");
  }
  solved->iterations += offset;
  return solved;
}

}  // namespace

nlohmann::json WorkersJson(const FarmReport& r) {
  return {{"remote_rows", r.remote_rows},         {"verified_rows", r.verified_rows},
          {"verify_seconds", r.verify_seconds},   {"remote_build_seconds", r.remote_build_seconds},
          {"rejected_blocks", r.rejected_blocks}, {"rejected", r.rejected}};
}

absl::StatusOr<EncodedResult> RunStoredJob(const v1::Job& job, const RunContext& c) {
  if (job.options().has_viewfactors()) return RunStoredViewFactorJob(job, c);
  const ScopedThreadCount job_threads(c.threads);  // the light probe and the rest too
  const auto start = Clock::now();
  absl::StatusOr<std::shared_ptr<const LoadedScene>> loaded =
      c.scenes->Get(job.scene_sha256(), job.options().import_options());
  if (!loaded.ok()) return loaded.status();
  absl::StatusOr<JobOptions> options = FromProto(job.options());
  if (!options.ok()) return options.status();
  options->form_factors.threads = c.threads;
  absl::StatusOr<uint64_t> row_budget =
      RowMemoryBudget((*loaded)->PatchCount(JobMeshOptions(*options)), *options, c.max_memory);
  if (!row_budget.ok()) return row_budget.status();
  options->spill.memory_limit = *row_budget;  // > 0: the rows spill (and the report says so)
  const double load_seconds = SecondsSince(start);
  c.on_phase(v1::PHASE_PREPARE, 0);
  // PrepareJob takes its own copy of the scene, and the mesh the job's count built if it is
  // still there.
  std::optional<GroupedMesh> counted = (*loaded)->TakeMesh(JobMeshOptions(*options));
  absl::StatusOr<std::unique_ptr<PreparedJob>> prepared =
      counted ? PrepareJob((*loaded)->scene, *std::move(counted), *options)
              : PrepareJob((*loaded)->scene, *options);
  if (!prepared.ok()) return prepared.status();
  const PreparedJob& p = **prepared;
  const int64_t n = static_cast<int64_t>(p.Unknowns());
  if (Stopped(c)) return absl::CancelledError("stopped before form-factor rows");
  // The result's bytes that do not depend on B, encoded beside the rows, so that after the
  // solve only B and the report are.
  std::future<ResultEncoder> encoder =
      std::async(std::launch::async, [&p] { return ResultEncoder(p.mesh); });

  // Flushed before each phase change and after the last iteration.
  ProgressThrottle throttle(*c.hub, kProgressInterval,
                            std::chrono::milliseconds(c.snapshot_interval_ms));
  c.on_phase(v1::PHASE_ROWS, n);
  // Stores row blocks behind the row builders, into the solve; on an early return
  // (shutdown, error) it stores what is queued so that it is kept for the resume.
  RowBlockWriter writer(*c.store, job.job_id(),
                        static_cast<uint32_t>(std::max(1, options->form_factors.block_size)),
                        c.checkpoint_seconds, RowBlockWriter::kDefaultMaxGroupBytes, c.fail);
  struct FinishWriter {  // on every return: drop the queue when cancelled, else store it
    RowBlockWriter& writer;
    const RunContext& c;
    ~FinishWriter() { writer.Finish(!(c.cancelled && c.cancelled->load())); }
  } finish_writer{writer, c};
  FarmReport farm_report;
  absl::StatusOr<JobRows> rows = BuildStoredRows(job, p, options->form_factors, *row_budget, c,
                                                 writer, throttle, &farm_report);
  if (!rows.ok()) return rows.status();

  throttle.Flush();
  c.on_phase(v1::PHASE_SOLVE, n);
  const auto solve_start = Clock::now();
  absl::StatusOr<SolveResult> solved = SolveStored(job, p, *rows, options->solver, c, throttle);
  if (!solved.ok()) return solved.status();
  throttle.Flush();  // the last iteration's progress and B go before the job's final event
  writer.Finish(/*drain=*/false);  // solved: the row blocks are about to be deleted
  // The report of `radflux solve` (MakeJobReport), from the same pieces.
  JobResult result;
  result.job = *std::move(prepared);
  result.form_factors = std::move(rows->matrix);
  result.row_store = std::move(rows->store);
  result.row_stats = rows->stats;
  result.solve = *std::move(solved);
  result.timings.mesh = result.job->mesh_seconds;
  result.timings.embree = result.job->embree_seconds;
  result.timings.rows = rows->seconds;
  result.timings.solve = SecondsSince(solve_start);
  if (absl::Status s = PushDownGroupedSolve(*options, result); !s.ok()) return s;
  if (absl::Status s = FindIndirect(result); !s.ok()) return s;
  const auto encode_start = Clock::now();
  nlohmann::json report_json = MakeJobReport(result, *options, (*loaded)->name);
  report_json["workers"] = WorkersJson(farm_report);
  const std::string report = report_json.dump(2);
  absl::StatusOr<EncodedResult> encoded =
      encoder.get().Finish(result.solve, result.indirect, report);
  if (encoded.ok() && !result.solve.converged) {
    encoded->converged = false;
    encoded->message =
        absl::StrFormat("not converged: residual %.3g after %d iterations (tolerance %.3g)",
                        result.solve.residual, result.solve.iterations, options->solver.tolerance);
  }
  if (encoded.ok() && result.solved_balance->ok() && !(*result.solved_balance)->Ok()) {
    encoded->energy_balance_ok = false;
    encoded->message = absl::StrCat(encoded->message, encoded->message.empty() ? "" : "; ",
                                    (*result.solved_balance)->OffMessage());
  }
  spdlog::debug(
      "job {}: ms scene load {:.1f}, mesh+embree {:.1f}, rows {:.1f}, solve {:.1f}, "
      "result encoding {:.1f}",
      job.job_id(), 1e3 * load_seconds, 1e3 * (result.timings.mesh + result.timings.embree),
      1e3 * result.timings.rows, 1e3 * result.timings.solve, 1e3 * SecondsSince(encode_start));
  return encoded;
}

}  // namespace radflux
