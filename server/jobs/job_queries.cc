// JobManager's queries and cancel for a caller: a job, a scene, the list of jobs, each only
// when the caller's principal may see it (Principal::Sees).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>

#include "absl/strings/str_cat.h"
#include "server/jobs/job_manager.h"
#include "wire/proto_convert.h"

namespace radflux {

absl::StatusOr<v1::Job> JobManager::VisibleJob(const std::string& job_id,
                                               const Principal& caller) {
  absl::StatusOr<v1::Job> job = store_.GetJob(job_id);
  if (job.ok() && !caller.Sees(job->owner())) {
    return absl::NotFoundError(absl::StrCat("no job ", job_id));  // as JobStore::GetJob says it
  }
  return job;
}

absl::StatusOr<v1::Job> JobManager::Cancel(const std::string& job_id, const Principal& caller) {
  absl::StatusOr<v1::Job> job = VisibleJob(job_id, caller);
  if (!job.ok() || IsTerminal(job->state())) return job;
  {
    std::lock_guard lock(mu_);
    if (auto it = running_.find(job_id); it != running_.end()) {
      it->second->cancel_requested = true;
      it->second->cancelled = true;
      it->second->stop = true;
      spdlog::info("job {}: cancel requested by {}", job_id, caller.name);
      return *job;
    }
    auto queued = std::find(queue_.begin(), queue_.end(), job_id);
    if (queued == queue_.end()) return *job;  // finishing right now
    queue_.erase(queued);
  }
  store_.RemoveWorkFiles(job_id);
  (void)Transition(*job, v1::JOB_STATE_CANCELLED, job->phase(), "cancelled while queued");
  return *job;
}

absl::StatusOr<v1::Job> JobManager::Get(const std::string& job_id, const Principal& caller) {
  absl::StatusOr<v1::Job> job = VisibleJob(job_id, caller);
  // Synced after the read: whatever it saw is durable before the client hears of it.
  if (absl::Status s = store_.SyncCommits(); !s.ok()) return s;
  return job;
}

absl::Status JobManager::CheckSceneVisible(const std::string& sha256, const Principal& caller) {
  if (caller.admin || store_.SceneOwnedBy(sha256, caller.name)) return absl::OkStatus();
  return absl::NotFoundError(  // as JobStore::GetScene says it
      absl::StrCat("no scene with sha256 ", sha256, "; upload it first"));
}

absl::StatusOr<StoredScene> JobManager::GetScene(const std::string& sha256,
                                                 const Principal& caller) {
  if (absl::Status s = CheckSceneVisible(sha256, caller); !s.ok()) return s;
  return store_.GetScene(sha256);
}

absl::StatusOr<v1::ListJobsResponse> JobManager::List(const v1::ListJobsRequest& request,
                                                      const Principal& caller) {
  JobFilter filter;
  for (int s : request.states()) filter.states.push_back(static_cast<v1::JobState>(s));
  filter.scene_sha256 = request.scene_sha256();
  if (!caller.admin) filter.owner = caller.name;
  filter.limit = request.page_size() <= 0 ? 100 : std::min(request.page_size(), 1000);
  if (!request.page_token().empty()) {
    char* end = nullptr;
    const long offset = std::strtol(request.page_token().c_str(), &end, 10);
    if (*end != '\0' || offset < 0) return absl::InvalidArgumentError("bad page_token");
    filter.offset = static_cast<int>(offset);
  }
  absl::StatusOr<std::vector<v1::Job>> jobs = store_.ListJobs(filter);
  if (!jobs.ok()) return jobs.status();
  // Synced after the read: whatever it saw is durable before the client hears of it.
  if (absl::Status s = store_.SyncCommits(); !s.ok()) return s;
  v1::ListJobsResponse response;
  for (v1::Job& job : *jobs) *response.add_jobs() = std::move(job);
  if (response.jobs_size() == filter.limit) {
    response.set_next_page_token(std::to_string(filter.offset + filter.limit));
  }
  return response;
}

}  // namespace radflux
