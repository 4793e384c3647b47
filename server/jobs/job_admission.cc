// JobManager's admission: an upload checked and stored, and a submit checked against the
// server's and its principal's limits (running jobs, patches, memory, disk) and its
// request_id before it becomes a job.
#include <openssl/rand.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "server/jobs/cpu_time.h"
#include "server/jobs/job_manager.h"
#include "server/jobs/row_budget.h"
#include "server/jobs/view_factor_runner.h"
#include "server/store/disk_space.h"
#include "server/store/request_hash.h"
#include "solver/pipeline.h"
#include "solver/scene/validation.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

// Upper bound of the patch count of subdividing with max_edge, without subdividing.
double MaxEdgePatchBound(const Scene& scene, double max_edge) {
  double bound = 0;
  for (const Face& face : scene.faces) {
    const std::vector<Vec3> polygon = FacePolygon(scene, face);
    double longest = 0;
    for (size_t k = 0; k < polygon.size(); ++k) {
      const Vec3& a = polygon[k];
      const Vec3& b = polygon[(k + 1) % polygon.size()];
      longest = std::max(longest, std::hypot(a.x - b.x, a.y - b.y, a.z - b.z));
    }
    const double per_edge = std::ceil(longest / max_edge) + 1;
    bound += per_edge * per_edge * static_cast<double>(polygon.size());
  }
  return bound;
}

// Disk a job may write: its row blocks (stored compressed), the rows it spills (at most
// all), its checkpoint and its result: bounded by its memory estimate with its rows in
// memory, which counts the rows twice (for cg's copy) besides mesh and solver vectors.
uint64_t JobDiskNeed(uint64_t patches, const JobOptions& options) {
  JobOptions in_memory = options;
  in_memory.spill.memory_limit = 0;
  return EstimateJobBytes(patches, in_memory);
}

std::string NewJobId() {
  unsigned char bytes[8];
  RAND_bytes(bytes, sizeof(bytes));
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id = "job-";
  for (unsigned char b : bytes) {
    id.push_back(kHex[b >> 4]);
    id.push_back(kHex[b & 15]);
  }
  return id;
}

}  // namespace

absl::StatusOr<std::unique_ptr<SceneUpload>> JobManager::StartUpload(
    const v1::SceneHeader& header) {
  absl::StatusOr<uint64_t> size = ScenePayloadSize(header);
  if (!size.ok()) return size.status();
  if (*size > options_.max_upload) {
    return absl::ResourceExhaustedError(absl::StrCat("scene of ", *size,
                                                     " bytes exceeds the upload limit of ",
                                                     options_.max_upload, " bytes (--max-upload)"));
  }
  return store_.StartUpload(header);
}

absl::StatusOr<v1::SceneRef> JobManager::AddScene(const v1::SceneHeader& header,
                                                  SceneUpload& upload, const Principal& caller) {
  std::string sha;
  v1::SceneRef ref;
  std::string name;
  {  // the scene is in memory in this block only: it is stored from its files
    absl::StatusOr<StoredScene> scene = upload.Finish(&sha);
    if (!scene.ok()) return scene.status();
    if (!header.sha256().empty() && header.sha256() != sha) {
      return absl::DataLossError(
          absl::StrCat("upload hashes to ", sha, ", not the declared ", header.sha256()));
    }
    if (scene->name.empty()) {
      scene->name = !scene->files.empty() ? scene->files[0].path
                    : scene->mesh.empty() ? "scene.obj"
                                          : "mesh";
    }
    name = scene->name;
    // Checked with the default import rules; a job's own (--strict, --emit, ...) are applied
    // when it is submitted, so a scene lit only by --emit uploads without an emitter.
    absl::StatusOr<Scene> loaded = LoadStoredScene(*std::move(scene), ImportOptions{});
    if (!loaded.ok()) return absl::InvalidArgumentError(std::string(loaded.status().message()));
    if (absl::Status s = ValidateScene(*loaded, /*require_emitter=*/false); !s.ok()) {
      return absl::InvalidArgumentError(s.message());
    }
    ref.set_faces(loaded->faces.size());
    ref.set_materials(loaded->materials.size());
  }
  ref.set_sha256(sha);
  // already_stored tells the caller of its own uploads only: whether another principal
  // uploaded the same bytes stays unsaid.
  const bool stored = store_.HasScene(sha);
  ref.set_already_stored(stored && store_.SceneOwnedBy(sha, caller.name));
  if (!stored) {
    if (absl::Status s = store_.PutScene(sha, name, upload); !s.ok()) return s;
    spdlog::info("scene {} stored ({}, {} faces)", sha.substr(0, 12), name, ref.faces());
  }
  if (absl::Status s = store_.AddSceneOwner(sha, caller.name); !s.ok()) return s;
  return ref;
}

absl::StatusOr<JobManager::DiskNeed> JobManager::CheckLimits(const v1::SubmitJobRequest& request,
                                                 const Principal& caller) {
  if (request.options().has_viewfactors()) return CheckViewFactorLimits(request, caller);
  absl::StatusOr<std::shared_ptr<const LoadedScene>> loaded =
      scenes_.Get(request.scene_sha256(), request.options().import_options());
  if (!loaded.ok()) return loaded.status();
  const Scene& scene = (*loaded)->scene;
  absl::StatusOr<JobOptions> options = FromProto(request.options());
  if (!options.ok()) return options.status();
  if (absl::Status s = ValidateJobOptions(*options); !s.ok()) return s;
  const int64_t max_patches = options_.max_patches;
  const auto too_many = [&](double n) {
    // A bound past any integer is written as a float, never cast (--max-edge 1e-300 bounds
    // the Cornell box past the largest double: it wrapped to -9223372036854775808).
    const std::string count = n < 1e15         ? absl::StrCat(static_cast<int64_t>(n))
                              : std::isfinite(n) ? absl::StrFormat("about %.3g", n)
                                                 : std::string("more than 1e+308");
    return absl::ResourceExhaustedError(absl::StrCat("job would mesh ", count,
                                                     " patches; this server allows at most ",
                                                     max_patches, " (--max-patches)"));
  };
  if (max_patches > 0 && options->mesh.target_patches > max_patches) {
    return too_many(static_cast<double>(options->mesh.target_patches));
  }
  if (max_patches > 0 && options->mesh.max_edge > 0) {
    const double bound = MaxEdgePatchBound(scene, options->mesh.max_edge);
    if (bound > 4.0 * static_cast<double>(max_patches)) return too_many(bound);
  }
  const uint64_t patches = (*loaded)->PatchCount(JobMeshOptions(*options));
  if (caller.limits.patches > 0 && patches > static_cast<uint64_t>(caller.limits.patches)) {
    return absl::ResourceExhaustedError(
        absl::StrCat("job would mesh ", patches, " patches; principal '", caller.name,
                     "' may submit at most ", caller.limits.patches, " a job (its limit patches)"));
  }
  if (absl::Status s =
          RowMemoryBudget(patches, *options, PerJobMemoryLimit(options_.max_memory)).status();
      !s.ok()) {
    return s;
  }
  return DiskNeed{JobDiskNeed(patches, *options), patches};
}

absl::StatusOr<JobManager::DiskNeed> JobManager::CheckViewFactorLimits(
    const v1::SubmitJobRequest& request, const Principal& caller) {
  absl::StatusOr<StoredScene> stored = store_.GetScene(request.scene_sha256());
  if (!stored.ok()) return stored.status();
  absl::StatusOr<ViewFactorRun> run = PrepareViewFactorRun(request.options(), *std::move(stored));
  if (!run.ok()) return run.status();
  // A surface is a row: the patch limits bound the matrix's rows (and, integrating patch rows,
  // the patches asked for).
  const int64_t asked = std::max(static_cast<int64_t>(run->surfaces),
                                 run->options.integration == ViewFactorIntegration::kPatches
                                     ? run->options.job.mesh.target_patches
                                     : 0);
  if (options_.max_patches > 0 && asked > options_.max_patches) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "view-factor job of ", asked, " surfaces or patches; this server allows at most ",
        options_.max_patches, " (--max-patches)"));
  }
  if (caller.limits.patches > 0 && asked > caller.limits.patches) {
    return absl::ResourceExhaustedError(
        absl::StrCat("view-factor job of ", asked, " surfaces or patches; principal '",
                     caller.name, "' may submit at most ", caller.limits.patches,
                     " a job (its limit patches)"));
  }
  return DiskNeed{ViewFactorDiskBound(*run), static_cast<uint64_t>(run->surfaces)};
}

absl::Status JobManager::CheckRunningJobs(const Principal& caller) {
  const int64_t limit = caller.limits.running_jobs;
  if (limit <= 0) return absl::OkStatus();
  absl::StatusOr<int64_t> unfinished = store_.CountUnfinishedJobs(caller.name);
  if (!unfinished.ok()) return unfinished.status();
  if (*unfinished < limit) return absl::OkStatus();
  return absl::ResourceExhaustedError(
      absl::StrCat("principal '", caller.name, "' has ", *unfinished,
                   " jobs queued or running, its limit running_jobs is ", limit,
                   "; wait for one to end or cancel one"));
}

absl::StatusOr<v1::Job> JobManager::Submit(const v1::SubmitJobRequest& request,
                                           const Principal& caller) {
  // A job is made durable before any client hears of it (it may be one whose first submit
  // is still making it durable).
  const auto durable = [this](absl::StatusOr<v1::Job> job) -> absl::StatusOr<v1::Job> {
    if (absl::Status s = store_.SyncCommits(); job.ok() && !s.ok()) return s;
    return job;
  };
  if (request.request_id().size() > kMaxRequestIdBytes) {
    return absl::InvalidArgumentError(absl::StrCat("request_id of ", request.request_id().size(),
                                                   " bytes: at most ", kMaxRequestIdBytes));
  }
  const std::string request_hash = SubmitRequestHash(request.scene_sha256(), request.options());
  absl::StatusOr<std::optional<v1::Job>> earlier =
      store_.FindRequest(caller.name, request.request_id(), request_hash);
  if (!earlier.ok()) return earlier.status();
  if (earlier->has_value()) return durable(**earlier);
  const auto check_start = std::chrono::steady_clock::now();
  if (absl::Status s = CheckSceneVisible(request.scene_sha256(), caller); !s.ok()) return s;
  if (absl::Status s = store_.EnsureSpaceReserve(); !s.ok()) return s;
  const absl::StatusOr<DiskNeed> disk_need = CheckLimits(request, caller);
  if (!disk_need.ok()) return disk_need.status();
  const auto create_start = std::chrono::steady_clock::now();
  v1::Job job;
  job.set_job_id(NewJobId());
  job.set_scene_sha256(request.scene_sha256());
  *job.mutable_options() = request.options();
  job.set_state(v1::JOB_STATE_QUEUED);
  job.set_created_unix_ms(NowUnixMs());
  job.set_request_id(request.request_id());
  job.set_owner(caller.name);
  absl::StatusOr<v1::Job> created;
  {
    std::lock_guard admit(admit_mu_);  // no other submit between the checks and the insert
    if (absl::Status s = CheckRunningJobs(caller); !s.ok()) return s;
    if (absl::Status s = CheckDiskRoom(*disk_need); !s.ok()) return s;
    if (options_.submit_delay_ms > 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(options_.submit_delay_ms));
    }
    {
      std::lock_guard lock(mu_);
      if (stopping_) return absl::UnavailableError("server is shutting down");
      if (queue_.size() >= options_.max_queued) {
        return absl::ResourceExhaustedError(
            absl::StrCat("job queue is full (", options_.max_queued, " jobs waiting)"));
      }
    }
    // Committed without its fsync, queued, and then made durable: the job starts (its first
    // steps need no durable row) while the fsync runs, and the client hears of it only after.
    created = store_.CreateJob(job, request_hash, /*sync=*/false);
    if (created.ok() && created->job_id() == job.job_id()) {
      std::lock_guard lock(mu_);
      disk_needs_.emplace(job.job_id(), disk_need->bytes);  // held before the next check
    }
  }
  if (!created.ok() || created->job_id() != job.job_id()) return durable(created);  // a retry
  const auto sync_start = std::chrono::steady_clock::now();
  {
    std::lock_guard lock(mu_);
    queue_.push_back(job.job_id());
    v1::JobEvent event;
    event.set_state(v1::JOB_STATE_QUEUED);
    HubLocked(job.job_id())->Publish(event);
  }
  cv_.notify_one();
  spdlog::info("job {}: QUEUED (scene {}, principal {})", job.job_id(),
               job.scene_sha256().substr(0, 12), caller.name);
  if (absl::Status s = store_.SyncCommits(); !s.ok()) {
    spdlog::error("job {}: {}", job.job_id(), std::string(s.message()));
    return s;
  }
  spdlog::debug("job {}: ms limits checked {:.1f}, job stored {:.1f}, made durable {:.1f}",
                job.job_id(), MsBetween(check_start, create_start),
                MsBetween(create_start, sync_start),
                MsBetween(sync_start, std::chrono::steady_clock::now()));
  return job;
}

uint64_t JobManager::ReservedDiskBytes() {
  std::map<std::string, uint64_t> needs;
  {
    std::lock_guard lock(mu_);
    needs = disk_needs_;
  }
  uint64_t reserved = 0;
  for (const auto& [job_id, need] : needs) {
    const uint64_t written = DirectoryBytes(store_.JobDir(job_id));  // already off the free space
    reserved += need > written ? need - written : 0;
  }
  return reserved;
}

void JobManager::TrackDiskNeed(const v1::Job& job) {
  if (job.patches() <= 0) return;
  {
    std::lock_guard lock(mu_);
    if (disk_needs_.count(job.job_id()) > 0) return;
  }
  absl::StatusOr<JobOptions> options = FromProto(job.options());
  if (!options.ok()) return;  // the job fails on them itself
  const uint64_t need = JobDiskNeed(static_cast<uint64_t>(job.patches()), *options);
  std::lock_guard lock(mu_);
  disk_needs_.emplace(job.job_id(), need);
}

absl::Status JobManager::CheckDiskRoom(const DiskNeed& need) {
  const absl::StatusOr<uint64_t> free = FreeDiskBytes(store_.data_dir());
  if (!free.ok()) return absl::OkStatus();
  const uint64_t reserved = ReservedDiskBytes();
  if (reserved <= *free && need.bytes <= *free - reserved) return absl::OkStatus();
  constexpr double kMiB = 1 << 20;
  return absl::ResourceExhaustedError(absl::StrFormat(
      "job would need up to %.1f MiB of disk (%d patches: rows, checkpoint, result); the data "
      "directory %s has %.1f MiB free, of which the unfinished jobs may still write %.1f MiB",
      static_cast<double>(need.bytes) / kMiB, need.patches, store_.data_dir(),
      static_cast<double>(*free) / kMiB, static_cast<double>(reserved) / kMiB));
}

}  // namespace radflux
