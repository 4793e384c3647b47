// JobManager's hubs (one per job that has watchers or runs) and the results it serves
// from them, from memory or from the store.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "absl/strings/str_cat.h"
#include "server/jobs/cpu_time.h"
#include "server/jobs/job_manager.h"
#include "server/store/result_codec.h"
#include "wire/proto_convert.h"

namespace radflux {

std::shared_ptr<JobHub> JobManager::HubLocked(const std::string& job_id) {
  std::shared_ptr<JobHub>& hub = hubs_[job_id];
  if (!hub) hub = std::make_shared<JobHub>(job_id);
  return hub;
}

std::shared_ptr<JobHub> JobManager::RebuildHubLocked(const v1::Job& job, uint64_t base) {
  auto hub = std::make_shared<JobHub>(job.job_id(), base);
  hubs_[job.job_id()] = hub;
  v1::JobEvent event;
  event.set_state(job.state());
  event.set_phase(job.phase());
  event.set_message(job.message());
  CopyVerdict(job, event);
  hub->Publish(event);
  if (IsTerminal(job.state())) {
    hub->Close();
    RetireHubLocked(job.job_id());
  }
  return hub;
}

void JobManager::RetireHubLocked(const std::string& job_id) {
  constexpr size_t kFinishedHubsKept = 64;
  finished_hubs_.push_back(job_id);
  while (finished_hubs_.size() > kFinishedHubsKept) {
    hubs_.erase(finished_hubs_.front());
    finished_hubs_.pop_front();
  }
}

absl::StatusOr<std::shared_ptr<JobHub>> JobManager::Hub(const std::string& job_id,
                                                        const Principal& caller) {
  // The store says whose the job is (and what to rebuild a history from).
  absl::StatusOr<v1::Job> job = VisibleJob(job_id, caller);
  if (!job.ok()) return job.status();
  {
    std::lock_guard lock(mu_);
    if (auto it = hubs_.find(job_id); it != hubs_.end()) return it->second;
  }
  absl::StatusOr<uint64_t> base = store_.NextHistoryBase(job_id);
  if (!base.ok()) return base.status();
  std::lock_guard lock(mu_);
  if (auto it = hubs_.find(job_id); it != hubs_.end()) return it->second;
  return RebuildHubLocked(*job, *base);
}

absl::StatusOr<std::vector<v1::ResultChunk>> JobManager::Result(const std::string& job_id,
                                                                const Principal& caller,
                                                                bool report_only) {
  absl::StatusOr<v1::Job> job = VisibleJob(job_id, caller);
  if (!job.ok()) return job.status();
  if (job->state() != v1::JOB_STATE_SUCCEEDED) {
    return absl::FailedPreconditionError(
        absl::StrCat("job ", job_id, " has no result: it is ", v1::JobState_Name(job->state()),
                     job->message().empty() ? "" : " (" + job->message() + ")"));
  }
  const auto read_start = std::chrono::steady_clock::now();
  std::shared_ptr<const std::string> bytes = recent_results_.Get(job_id);
  const bool in_memory = bytes != nullptr;
  if (!in_memory) {
    absl::StatusOr<std::string> read = store_.GetResult(job_id);
    if (absl::IsDataLoss(read.status()) || absl::IsNotFound(read.status())) {
      return RecomputeResult(*std::move(job), read.status());
    }
    if (!read.ok()) return read.status();
    bytes = std::make_shared<const std::string>(*std::move(read));
  }
  absl::StatusOr<std::vector<v1::ResultChunk>> chunks = DecodeResultChunks(*bytes, report_only);
  spdlog::debug("job {}: ms result {} and decoded {:.1f}", job_id,
                in_memory ? "kept in memory" : "read",
                MsBetween(read_start, std::chrono::steady_clock::now()));
  if (chunks.ok() && !chunks->empty()) *(*chunks)[0].mutable_header()->mutable_job() = *job;
  return chunks;
}

absl::Status JobManager::RecomputeResult(v1::Job job, const absl::Status& why) {
  const std::string& job_id = job.job_id();
  const absl::Status recomputing = absl::UnavailableError(absl::StrCat(
      "job ", job_id, ": its stored result was lost or corrupt on the server and is being "
      "computed again; watch the job and ask for its result when it has succeeded"));
  absl::StatusOr<uint64_t> base = store_.NextHistoryBase(job_id);
  if (!base.ok()) return base.status();
  TrackDiskNeed(job);
  {
    std::lock_guard lock(mu_);
    if (stopping_) return absl::UnavailableError("server is shutting down");
    if (running_.count(job_id) > 0 ||
        std::find(queue_.begin(), queue_.end(), job_id) != queue_.end()) {
      return recomputing;  // another call found it first
    }
    spdlog::error("job {}: SUCCEEDED but its result is unreadable ({}); computing it again",
                  job_id, std::string(why.message()));
    store_.DiscardResult(job_id);
    job.set_state(v1::JOB_STATE_QUEUED);
    job.set_phase(v1::PHASE_UNSPECIFIED);
    job.set_message("stored result lost or corrupt; computing it again");
    job.clear_finished_unix_ms();
    if (absl::Status s = store_.UpdateJob(job); !s.ok()) return s;
    // The closed hub goes: watchers from now on follow the new run.
    finished_hubs_.erase(std::remove(finished_hubs_.begin(), finished_hubs_.end(), job_id),
                         finished_hubs_.end());
    RebuildHubLocked(job, *base);
    queue_.push_back(job_id);
  }
  cv_.notify_one();
  return recomputing;
}

}  // namespace radflux
