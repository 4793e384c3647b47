// JobManager: accepts jobs, keeps them in the job store, runs up to `jobs` of them at once
// on worker threads (sharing `threads` OpenMP threads), and publishes their events to
// per-job hubs. On Start it requeues every job a previous run left unfinished.
// Every method is thread-safe; the blocking ones (disk, parsing) must not run on gRPC
// reactor threads.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/radiosity.pb.h"
#include "server/jobs/job_hub.h"
#include "server/jobs/principal.h"
#include "server/jobs/recent_map.h"
#include "server/jobs/scene_cache.h"
#include "server/store/job_store.h"

namespace radflux {

class RowFarm;
struct JobOptions;

struct ManagerOptions {
  int jobs = 1;                        // jobs running at once
  int threads = 0;                     // OpenMP threads shared by the running jobs (0 = all cores)
  int64_t max_patches = 2'000'000;     // larger jobs are refused (RESOURCE_EXHAUSTED)
  uint64_t max_memory = 0;             // bytes per job by EstimateJobBytes (0 = half the RAM)
  uint64_t max_upload = 256ull << 20;  // bytes of OBJ + MTL per scene
  int max_concurrent_uploads = 4;      // uploads in progress at once; more are refused
  size_t max_queued = 1000;            // queued jobs beyond this are refused
  double checkpoint_seconds = 1.0;     // at most one row-block and one solver checkpoint per job
                                       // per interval (0 = after every block / iteration)
  int solve_delay_ms = 0;              // testing: sleep after each solver iteration (widens the
                                       // window in which a test can kill the server mid-solve)
  int snapshot_interval_ms = 100;      // at most one snapshot per job per this interval (the
                                       // newest; the last iteration's always), 0 = every one
  RowFarm* farm = nullptr;             // worker nodes share the row blocks through it (may be null)
  int block_delay_ms = 0;              // testing: sleep after each row block built on the server
  int submit_delay_ms = 0;             // testing: sleep in a submit between its checks and insert
  // The limits of a job's owner when it runs (its cpu_seconds; null: no limits).
  std::function<PrincipalLimits(const std::string& owner)> limits_of;
};

// The longest request_id a submit may carry.
inline constexpr size_t kMaxRequestIdBytes = 128;

class JobManager {
 public:
  JobManager(JobStore& store, ManagerOptions options);
  ~JobManager();  // Shutdown()
  JobManager(const JobManager&) = delete;
  JobManager& operator=(const JobManager&) = delete;

  // Requeues unfinished jobs and starts the workers.
  absl::Status Start();
  // Stops the workers: running jobs checkpoint and stay RUNNING in the store, to be
  // resumed by the next Start. Idempotent.
  void Shutdown();

  const ManagerOptions& options() const { return options_; }

  // Every call below is made for a `caller` (Principal): jobs and scenes are its own, and
  // another principal's job or scene is NOT_FOUND exactly as a job or scene that does not
  // exist (ids do not leak); an admin sees all.

  // An upload of the scene `header` declares, streamed to disk (SceneUpload): INVALID_ARGUMENT
  // for a header ScenePayloadSize refuses, RESOURCE_EXHAUSTED past --max-upload.
  absl::StatusOr<std::unique_ptr<SceneUpload>> StartUpload(const v1::SceneHeader& header);
  // Finishes `upload` (all its bytes written), checks and parses the scene and stores it as
  // one of the caller's (INVALID_ARGUMENT with the loader's message; DATA_LOSS when it was
  // cut short or does not hash to header.sha256()). already_stored: the caller had uploaded
  // it before.
  absl::StatusOr<v1::SceneRef> AddScene(const v1::SceneHeader& header, SceneUpload& upload,
                                        const Principal& caller);
  // Validates and queues a job of the caller (RESOURCE_EXHAUSTED "disk full ..." while the
  // data directory cannot hold the store's space reserve; RESOURCE_EXHAUSTED naming the limit
  // and the principal when it has its running_jobs queued or running, or the job meshes more
  // than its patches), or returns the job of an earlier submit of the caller with the same
  // request id and the same scene and options; the same id with another request is
  // FAILED_PRECONDITION, an id longer than kMaxRequestIdBytes INVALID_ARGUMENT.
  // Everything that can be refused is refused here, before any work.
  absl::StatusOr<v1::Job> Submit(const v1::SubmitJobRequest& request, const Principal& caller);
  // Cancels a queued or running job (a finished job is returned unchanged).
  absl::StatusOr<v1::Job> Cancel(const std::string& job_id, const Principal& caller);
  absl::StatusOr<v1::Job> Get(const std::string& job_id, const Principal& caller);
  // The texts of a stored scene (NOT_FOUND when no scene has that address).
  absl::StatusOr<StoredScene> GetScene(const std::string& sha256, const Principal& caller);
  // The caller's jobs (an admin's: everyone's), newest first.
  absl::StatusOr<v1::ListJobsResponse> List(const v1::ListJobsRequest& request,
                                            const Principal& caller);
  // The event hub of a job (live, or a closed one-event history for a finished job).
  absl::StatusOr<std::shared_ptr<JobHub>> Hub(const std::string& job_id, const Principal& caller);
  // The result chunks of a SUCCEEDED job (FAILED_PRECONDITION before that); with
  // `report_only`, only the header and the report (GetResultRequest.report_only). A result
  // file lost or failing its check is computed again (RecomputeResult): UNAVAILABLE saying so.
  absl::StatusOr<std::vector<v1::ResultChunk>> Result(const std::string& job_id,
                                                      const Principal& caller,
                                                      bool report_only = false);

 private:
  struct Running {
    std::atomic<bool> stop{false};
    std::atomic<bool> cancelled{false};  // stop is for a cancel: the job's files will go
    bool cancel_requested = false;       // guarded by mu_
  };

  // The job if the caller may see it, else NOT_FOUND as for no such job.
  absl::StatusOr<v1::Job> VisibleJob(const std::string& job_id, const Principal& caller);
  // What a job may write to disk (JobDiskNeed), for CheckDiskRoom.
  struct DiskNeed {
    uint64_t bytes = 0;
    uint64_t patches = 0;
  };
  // The scene and options checks of a submit (server and caller limits, memory); the job's
  // disk need, checked against the free space by CheckDiskRoom with the insert.
  absl::StatusOr<DiskNeed> CheckLimits(const v1::SubmitJobRequest& request,
                                       const Principal& caller);
  // CheckLimits of a view-factor job: its model and options checked as `radflux viewfactors`
  // checks them, its surfaces against the patch limits, its files' size as its disk need.
  absl::StatusOr<DiskNeed> CheckViewFactorLimits(const v1::SubmitJobRequest& request,
                                                 const Principal& caller);
  // NOT_FOUND (as for no such scene) unless the caller uploaded the scene or is an admin.
  absl::Status CheckSceneVisible(const std::string& sha256, const Principal& caller);
  // RESOURCE_EXHAUSTED when the caller has its running_jobs limit of jobs unfinished.
  absl::Status CheckRunningJobs(const Principal& caller);
  // RESOURCE_EXHAUSTED when the job's disk need exceeds the data directory's free space
  // less what the unfinished jobs may still write (ReservedDiskBytes). Called under
  // admit_mu_ with the insert that records the need, so two submits cannot both take the
  // room of one.
  absl::Status CheckDiskRoom(const DiskNeed& need);
  // What the jobs of disk_needs_ may still write: each one's need less the bytes its
  // directory holds already.
  uint64_t ReservedDiskBytes();
  // Records an unfinished job's disk need once its patch count is known (a job requeued at
  // start that had meshed, or one meshing now); Submit records its own.
  void TrackDiskNeed(const v1::Job& job);
  void WorkerLoop();
  void RunOne(const std::string& job_id);
  // Stores the job's new state/phase, publishes it and logs one line. With `result_synced`
  // (SUCCEEDED, its result written in place but not yet fsynced: JobStore::PutResult
  // of a prepared file) the state is committed, and the commit made durable while that fsync runs;
  // the event is published once both are durable. Returns the store's status (a
  // failure is logged here: the callers that end a job have nothing more to do about it).
  absl::Status Transition(v1::Job& job, v1::JobState state, v1::Phase phase, const std::string& message,
                  std::future<absl::Status>* result_synced = nullptr);
  // On Start: every SUCCEEDED job whose result was never marked durable (an OS crash may
  // have cut short its fsync, which runs beside the SUCCEEDED commit's) has its result file
  // read and verified; when it is missing or corrupt, the job goes back to QUEUED (with a
  // message saying why) and computes its result again: the same B, the computation being
  // deterministic (rows still stored are reused; a solver checkpoint is not, so that cg,
  // whose resume agrees only within the tolerance, restarts as the first run did).
  absl::Status CheckResultsAtStart();
  // A SUCCEEDED job whose result file was found lost or corrupt (`why`) after it was marked
  // durable: the file is discarded and the job goes back to QUEUED (its watchers see a new
  // run) to compute the result again, bit-identical, from its scene (and rows still stored).
  // Returns UNAVAILABLE saying so, also when another call has requeued it already.
  absl::Status RecomputeResult(v1::Job job, const absl::Status& why);
  // On Start: queues a stored QUEUED or RUNNING job and rebuilds its event history.
  absl::Status RequeueAtStart(const v1::Job& job);
  std::shared_ptr<JobHub> HubLocked(const std::string& job_id);
  // A job's event history rebuilt from the store (after a restart, or when its finished hub
  // left memory): numbered after `base` (JobStore::NextHistoryBase), its first event the
  // job's stored state and phase; closed (and retired) when that state is terminal.
  std::shared_ptr<JobHub> RebuildHubLocked(const v1::Job& job, uint64_t base);
  // Notes that a job's hub is closed; only the newest kFinishedHubsKept closed hubs stay in
  // memory (with their last snapshot), older ones are dropped (watchers holding one keep it;
  // a later Hub() rebuilds a one-event history from the store).
  void RetireHubLocked(const std::string& job_id);

  JobStore& store_;
  SceneCache scenes_{store_};  // shared by the limits check and the jobs' start
  // The stored bytes of the last results of jobs that succeeded here (up to
  // kRecentResultBytes each): GetResult right after a job ends skips reading, verifying
  // and decompressing its file.
  RecentMap<std::string> recent_results_{2};
  const ManagerOptions options_;
  std::mutex admit_mu_;  // a submit's running_jobs and disk checks and its insert, one at a time
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::string> queue_;
  std::map<std::string, std::shared_ptr<Running>> running_;
  std::map<std::string, std::shared_ptr<JobHub>> hubs_;
  std::deque<std::string> finished_hubs_;  // closed hubs in hubs_, oldest first
  std::map<std::string, uint64_t> disk_needs_;  // unfinished jobs' disk estimates, bytes
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace radflux
