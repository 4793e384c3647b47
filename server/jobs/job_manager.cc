#include "server/jobs/job_manager.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "server/jobs/cpu_budget.h"
#include "server/jobs/cpu_time.h"
#include "server/jobs/job_runner.h"
#include "server/jobs/row_budget.h"
#include "server/store/result_codec.h"
#include "solver/core/parallel.h"
#include "solver/pipeline.h"
#include "solver/scene/validation.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

// Results up to this size stay in memory after their job succeeds (JobManager::Result).
constexpr size_t kRecentResultBytes = 64u << 20;

}  // namespace

JobManager::JobManager(JobStore& store, ManagerOptions options)
    : store_(store), options_(std::move(options)) {}

JobManager::~JobManager() { Shutdown(); }

absl::Status JobManager::Start() {
  absl::StatusOr<std::vector<v1::Job>> unfinished = store_.UnfinishedJobs();
  if (!unfinished.ok()) return unfinished.status();
  for (const v1::Job& job : *unfinished) {
    spdlog::info("job {}: {} at startup, requeued", job.job_id(), v1::JobState_Name(job.state()));
    if (absl::Status s = RequeueAtStart(job); !s.ok()) return s;
  }
  if (absl::Status s = CheckResultsAtStart(); !s.ok()) return s;
  for (int i = 0; i < std::max(1, options_.jobs); ++i)
    workers_.emplace_back([this] { WorkerLoop(); });
  return absl::OkStatus();
}

absl::Status JobManager::CheckResultsAtStart() {
  absl::StatusOr<std::vector<v1::Job>> unchecked = store_.UncheckedResults();
  if (!unchecked.ok()) return unchecked.status();
  for (v1::Job& job : *unchecked) {
    const absl::StatusOr<std::string> result = store_.GetResult(job.job_id());
    if (result.ok()) {
      if (absl::Status s = store_.MarkResultDurable(job.job_id()); !s.ok()) return s;
      continue;
    }
    spdlog::warn("job {}: SUCCEEDED but its result is unreadable ({}); computing it again",
                 job.job_id(), std::string(result.status().message()));
    store_.DiscardResult(job.job_id());
    job.set_state(v1::JOB_STATE_QUEUED);
    job.set_phase(v1::PHASE_UNSPECIFIED);
    job.set_message("result lost in a crash; computing it again");
    job.clear_finished_unix_ms();
    if (absl::Status s = store_.UpdateJob(job); !s.ok()) return s;
    if (absl::Status s = RequeueAtStart(job); !s.ok()) return s;
  }
  return absl::OkStatus();
}

absl::Status JobManager::RequeueAtStart(const v1::Job& job) {
  absl::StatusOr<uint64_t> base = store_.NextHistoryBase(job.job_id());
  if (!base.ok()) return base.status();
  TrackDiskNeed(job);
  std::lock_guard lock(mu_);
  queue_.push_back(job.job_id());
  RebuildHubLocked(job, *base);
  return absl::OkStatus();
}

void JobManager::Shutdown() {
  {
    std::lock_guard lock(mu_);
    if (stopping_ && workers_.empty()) return;
    stopping_ = true;
    for (auto& [id, running] : running_) running->stop = true;
  }
  cv_.notify_all();
  for (std::thread& t : workers_) t.join();
  workers_.clear();
}

absl::Status JobManager::Transition(v1::Job& job, v1::JobState state, v1::Phase phase,
                                    const std::string& message,
                                    std::future<absl::Status>* result_synced) {
  const v1::JobState from = job.state();
  job.set_state(state);
  job.set_phase(phase);
  job.set_message(message);
  if (IsTerminal(state)) job.set_finished_unix_ms(NowUnixMs());
  const auto update_start = std::chrono::steady_clock::now();
  absl::Status stored = store_.UpdateJob(job, /*sync=*/result_synced == nullptr);
  if (stored.ok() && result_synced != nullptr) stored = store_.SyncCommits();
  if (!stored.ok()) {
    spdlog::error("job {}: cannot store state: {}", job.job_id(), std::string(stored.message()));
  }
  const auto stored_end = std::chrono::steady_clock::now();
  bool result_durable = false;
  if (result_synced != nullptr) {
    // Reported, not undone: the result is in the file (and survives kill -9); if an OS
    // crash loses it, the next start computes it again (CheckResultsAtStart).
    const absl::Status s = result_synced->get();
    if (!s.ok()) spdlog::error("job {}: {}", job.job_id(), std::string(s.message()));
    result_durable = s.ok();
  }
  spdlog::debug("job {}: ms state stored {:.1f}, result synced {:.1f} later", job.job_id(),
                MsBetween(update_start, stored_end),
                MsBetween(stored_end, std::chrono::steady_clock::now()));
  std::shared_ptr<JobHub> hub;
  {
    std::lock_guard lock(mu_);
    hub = HubLocked(job.job_id());
  }
  v1::JobEvent event;
  event.set_state(state);
  event.set_phase(phase);
  event.set_message(message);
  if (state == v1::JOB_STATE_SUCCEEDED) CopyVerdict(job, event);
  hub->Publish(event);
  if (IsTerminal(state)) {
    hub->Close();
    std::lock_guard lock(mu_);
    RetireHubLocked(job.job_id());
    disk_needs_.erase(job.job_id());
  }
  if (result_durable) {  // after the event: the mark is for the next start only
    if (absl::Status s = store_.MarkResultDurable(job.job_id()); !s.ok()) {
      spdlog::warn("job {}: {}", job.job_id(), std::string(s.message()));
    }
  }
  spdlog::info("job {}: {} -> {} {}{}{}", job.job_id(), v1::JobState_Name(from),
               v1::JobState_Name(state), v1::Phase_Name(phase), message.empty() ? "" : ": ",
               message);
  return stored;
}

void JobManager::WorkerLoop() {
  for (;;) {
    std::string job_id;
    {
      std::unique_lock lock(mu_);
      cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job_id = queue_.front();
      queue_.pop_front();
      running_[job_id] = std::make_shared<Running>();
    }
    RunOne(job_id);
    std::lock_guard lock(mu_);
    running_.erase(job_id);
  }
}

void JobManager::RunOne(const std::string& job_id) {
  absl::StatusOr<v1::Job> loaded = store_.GetJob(job_id);
  if (!loaded.ok()) {
    spdlog::error("job {}: {}", job_id, std::string(loaded.status().message()));
    return;
  }
  v1::Job job = *std::move(loaded);
  std::shared_ptr<Running> running;
  std::shared_ptr<JobHub> hub;
  {
    std::lock_guard lock(mu_);
    running = running_[job_id];
    hub = HubLocked(job_id);
  }
  RunContext context;
  context.store = &store_;
  context.scenes = &scenes_;
  context.hub = hub.get();
  context.stop = &running->stop;
  context.cancelled = &running->cancelled;
  context.checkpoint_seconds = options_.checkpoint_seconds;
  context.solve_delay_ms = options_.solve_delay_ms;
  context.snapshot_interval_ms = options_.snapshot_interval_ms;
  context.farm = options_.farm;
  context.block_delay_ms = options_.block_delay_ms;
  context.max_memory = PerJobMemoryLimit(options_.max_memory);
  const int threads = ThreadCount(options_.threads);
  context.threads = std::max(1, threads / std::max(1, options_.jobs));
  std::mutex failure_mu;
  absl::Status failure;  // the first write of the job's files that failed (guarded)
  context.fail = [&](const absl::Status& error) {
    std::lock_guard lock(failure_mu);
    if (failure.ok()) failure = error;
    running->stop = true;
  };
  context.on_phase = [&](v1::Phase phase, int64_t patches) {
    if (patches > 0) job.set_patches(patches);
    TrackDiskNeed(job);
    if (absl::Status s = Transition(job, v1::JOB_STATE_RUNNING, phase, ""); !s.ok()) {
      context.fail(s);
    }
  };
  // The result file and its names are made durable while the job runs, so that storing the
  // result at the end takes one fsync instead of three (JobStore::PrepareResult).
  std::future<absl::Status> prepare =
      std::async(std::launch::async, [&] { return store_.PrepareResult(job_id); });
  const double thread_cpu = CpuMs(CLOCK_THREAD_CPUTIME_ID);
  const double process_cpu = CpuMs(CLOCK_PROCESS_CPUTIME_ID);
  absl::StatusOr<EncodedResult> result;
  {
    const double cpu_seconds = options_.limits_of ? options_.limits_of(job.owner()).cpu_seconds : 0;
    const CpuBudget budget(cpu_seconds, context.threads, [&] {
      context.fail(absl::ResourceExhaustedError(absl::StrFormat(
          "job reached the cpu_seconds limit of principal '%s': %g CPU seconds (%d threads x "
          "its running time)",
          job.owner(), cpu_seconds, context.threads)));
    });
    result = RunStoredJob(job, context);
  }
  // What the job cost the server's CPU while it ran: its own thread (with --threads 1 all
  // of its rows and solve), and every thread of the process (OpenMP and helper threads,
  // gRPC, watchers' writes, other calls), and the process's clock when the job started;
  // bench/watcher_cost.sh compares them with and without watchers.
  spdlog::debug("job {}: cpu ms job thread {:.2f}, process {:.2f}, process clock at start {:.2f}",
                job_id, CpuMs(CLOCK_THREAD_CPUTIME_ID) - thread_cpu,
                CpuMs(CLOCK_PROCESS_CPUTIME_ID) - process_cpu, process_cpu);
  const absl::Status prepared = prepare.get();
  if (!prepared.ok()) {
    spdlog::warn("job {}: {} (the result is stored atomically instead)", job_id,
                 std::string(prepared.message()));
  }
  bool cancelled;
  {
    std::lock_guard lock(mu_);
    cancelled = running->cancel_requested;
  }
  {
    std::lock_guard lock(failure_mu);
    if (!failure.ok() && !cancelled) result = failure;  // never a success with lost writes
  }
  // Work files go before the terminal transition: whoever sees the end sees them gone.
  if (result.ok()) {
    // Into the prepared file without its fsync, which then runs beside the SUCCEEDED
    // commit's (JobStore::SyncCommits) instead of before it: no client hears SUCCEEDED
    // before both are durable, except GetJob/ListJobs, which may see the commit durable
    // while the result's fsync still runs; after an OS crash in that window, the restart
    // finds the result unreadable and computes it again (CheckResultsAtStart).
    const auto put_start = std::chrono::steady_clock::now();
    absl::Status put = store_.PutResult(job_id, result->file, prepared.ok());
    const auto remove_start = std::chrono::steady_clock::now();
    if (put.ok()) store_.RemoveWorkFiles(job_id);
    if (put.ok() && result->bytes.size() <= kRecentResultBytes) {
      recent_results_.Put(job_id, std::make_shared<const std::string>(std::move(result->bytes)));
    }
    spdlog::debug("job {}: ms result {} {:.1f}, work files removed {:.1f}", job_id,
                  prepared.ok() ? "written" : "stored", MsBetween(put_start, remove_start),
                  MsBetween(remove_start, std::chrono::steady_clock::now()));
    if (put.ok()) {
      // The result's fsync, beside the commit's (a no-op when it was stored atomically).
      std::future<absl::Status> synced =
          std::async(std::launch::async, [&] { return store_.SyncResult(job_id); });
      job.set_converged(result->converged);
      job.set_energy_balance_ok(result->energy_balance_ok);
      (void)Transition(job, v1::JOB_STATE_SUCCEEDED, v1::PHASE_DONE, result->message, &synced);
    } else {
      store_.RemoveWorkFiles(job_id);
      (void)Transition(job, v1::JOB_STATE_FAILED, job.phase(), std::string(put.message()));
    }
  } else if (cancelled) {
    store_.RemoveWorkFiles(job_id);
    (void)Transition(job, v1::JOB_STATE_CANCELLED, job.phase(), "cancelled by request");
  } else if (result.status().code() == absl::StatusCode::kCancelled) {
    spdlog::info("job {}: suspended for shutdown in {}, resumes on restart", job_id,
                 v1::Phase_Name(job.phase()));
  } else {
    store_.RemoveWorkFiles(job_id);
    (void)Transition(job, v1::JOB_STATE_FAILED, job.phase(),
                     std::string(result.status().message()));
  }
}

}  // namespace radflux
