// JobStore: everything the server keeps on disk, in its data directory. Jobs and scenes
// are rows of an SQLite database (radflux.db); scene texts, form-factor row blocks,
// solver checkpoints and results are checksummed blob files (see blob_file.h) under
// scenes/ and jobs/<id>/. Every write is durable (fsynced) when the call returns, except
// UpdateJob of a RUNNING job, CreateJob(sync = false), UpdateJob(sync = false),
// PutResult(prepared = true) and MarkResultDurable, which survive kill -9 but not an OS crash
// (until SyncCommits, resp. SyncResult). A write that fails says what and where
// (disk_space.h: RESOURCE_EXHAUSTED "disk full writing ..." on a full disk) and leaves no
// partial file; a space reserve (disk_space.h) keeps room to record a job's end. Jobs and
// scenes belong to principals (owner); the schema and its migrations are store_schema.h,
// the scene files scene_store.cc, a job's files job_files.cc. Thread-safe.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/job.pb.h"
#include "server/store/disk_space.h"
#include "server/store/scene_upload.h"
#include "server/store/stored_codec.h"
#include "wire/stored_scene.h"

struct sqlite3;

namespace radflux {

// Sequence numbers of one event history of a job span fewer than 2^this.
inline constexpr int kHistorySequenceBits = 32;

// Which jobs ListJobs returns: newest first, `offset` jobs skipped, at most `limit`.
struct JobFilter {
  std::vector<v1::JobState> states;  // empty = all
  std::string scene_sha256;          // empty = all
  std::string owner;                 // empty = every principal's
  int offset = 0;
  int limit = 100;
};

class JobStore {
 public:
  // Opens (creating if needed) the store in `data_dir`. FAILED_PRECONDITION, saying how to
  // recover, when scenes/ or jobs/ hold files but the database radflux.db is gone. Temp files
  // of uploads cut short by a crash are removed (no upload outlives its server).
  static absl::StatusOr<std::unique_ptr<JobStore>> Open(const std::string& data_dir);
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  // Makes sure the space reserve is held (re-creating it after a full disk used it):
  // RESOURCE_EXHAUSTED "disk full ..." while the data directory cannot hold it.
  absl::Status EnsureSpaceReserve();

  bool HasScene(const std::string& sha256);
  // An upload of the scene `header` declares, its bytes streamed to temp files in scenes/
  // (see SceneUpload; INVALID_ARGUMENT for a header ScenePayloadSize refuses).
  absl::StatusOr<std::unique_ptr<SceneUpload>> StartUpload(const v1::SceneHeader& header);
  // Stores a finished upload (SceneUpload::Finish) as scene `sha256` named `name`: its files
  // renamed into place, its row added (kept when it was stored already).
  absl::Status PutScene(const std::string& sha256, const std::string& name, SceneUpload& upload);
  // NOT_FOUND when no scene has that address. DATA_LOSS (a message without server paths)
  // when its files are missing or fail their check: the scene is then marked missing
  // (HasScene false, owners kept), so that an upload of the same bytes stores it again.
  absl::StatusOr<StoredScene> GetScene(const std::string& sha256);
  // Records that principal `owner` uploaded the scene (idempotent).
  absl::Status AddSceneOwner(const std::string& sha256, const std::string& owner);
  // Whether principal `owner` uploaded the scene (scenes stored before owners existed are
  // the default principal's).
  bool SceneOwnedBy(const std::string& sha256, const std::string& owner);

  // The job principal `owner` created with `request_id` when it came with the same
  // request (`request_hash`, SubmitRequestHash); nullopt when there is none (or the id is
  // empty); FAILED_PRECONDITION naming the id and that job when it came with another.
  absl::StatusOr<std::optional<v1::Job>> FindRequest(const std::string& owner,
                                                     const std::string& request_id,
                                                     const std::string& request_hash);
  // Inserts a new job, owned by job.owner(). When job.request_id() is set and that owner
  // has a job with that request id, returns FindRequest's answer instead (the existing job
  // or FAILED_PRECONDITION) and inserts nothing. With `sync` false the insert is committed
  // without its fsync (it survives kill -9), to be made durable by SyncCommits, so that the
  // caller can start the job meanwhile.
  absl::StatusOr<v1::Job> CreateJob(const v1::Job& job, const std::string& request_hash,
                                    bool sync = true);
  // Makes every CreateJob(sync = false) and UpdateJob(sync = false) that returned before
  // this call durable: one fsync of the database's write-ahead log, which is where SQLite's
  // synchronous=FULL commit puts its own fsync, done here without the store's lock so that
  // other calls go on meanwhile. Immediate when there is nothing to sync.
  absl::Status SyncCommits();
  // Replaces the stored job with the same id. A RUNNING job's row is never fsynced (it
  // survives kill -9, not an OS crash); any other state is durable when this returns, or,
  // with `sync` false, once SyncCommits returns. A terminal state that finds the disk full
  // is written with the space reserve given back.
  absl::Status UpdateJob(const v1::Job& job, bool sync = true);
  // The job (with its owner) or NOT_FOUND.
  absl::StatusOr<v1::Job> GetJob(const std::string& job_id);
  // How many of principal `owner`'s jobs are QUEUED or RUNNING.
  absl::StatusOr<int64_t> CountUnfinishedJobs(const std::string& owner);
  absl::StatusOr<std::vector<v1::Job>> ListJobs(const JobFilter& filter);
  // Jobs QUEUED or RUNNING, oldest first: what a restarted server must finish.
  absl::StatusOr<std::vector<v1::Job>> UnfinishedJobs();
  // SUCCEEDED jobs, oldest first, whose result file has not been marked durable
  // (MarkResultDurable): those whose result a restart must check (and, if it is missing
  // or corrupt, compute again). Jobs of a store written before the mark existed have none.
  absl::StatusOr<std::vector<v1::Job>> UncheckedResults();
  // Records that the job's result file is durable (after SyncResult, or after a restart
  // read and verified it). Not fsynced itself: a mark lost in an OS crash only makes the
  // next start check that result again.
  absl::Status MarkResultDurable(const std::string& job_id);

  // The sequence number after which a rebuilt event history of the job starts (after a
  // restart, or when its finished hub left memory): k * 2^kHistorySequenceBits for its k-th
  // rebuild, recorded before it is returned. The first history of a job starts after 0, so
  // every history's numbers lie above all numbers of the job's earlier histories (each has
  // fewer than 2^32 events) and no watcher sees a number twice across a restart.
  absl::StatusOr<uint64_t> NextHistoryBase(const std::string& job_id);

  // Stores row blocks of a job in one file (one write and fsync however many blocks);
  // `name_index` names the file: the smallest block index in it, so it never replaces a
  // readable file (whose blocks are stored, hence never written again).
  absl::Status PutRowBlocks(const std::string& job_id, uint32_t name_index,
                            const std::vector<const StoredRowBlock*>& blocks);
  // Every stored row block of a job, file by file in the order of their names' index (so
  // the rows come roughly in row order, a file's worth in memory at a time); a file that
  // cannot be read is reported in `unreadable` (its blocks are simply not passed on).
  void ForEachRowBlock(const std::string& job_id, const std::function<void(StoredRowBlock)>& fn,
                       std::vector<absl::Status>* unreadable);
  absl::Status PutCheckpoint(const std::string& job_id, const SolverCheckpoint& checkpoint);
  absl::StatusOr<SolverCheckpoint> GetCheckpoint(const std::string& job_id);
  // Creates the job's directory and an empty result file in it, and makes both durable
  // (fsync of the file, the directory and jobs/), so that storing the result needs one fsync
  // (SyncResult). For when the job starts, off its critical path.
  absl::Status PrepareResult(const std::string& job_id);
  // Stores a finished job's result (a failed write removes the file), its blob file built already (`file`: the
  // BlobBuilder::File() of its serialized stream, see result_codec.h). `prepared`:
  // PrepareResult succeeded for the job; then `file` is written into that file without its
  // fsync (readable at once and after kill -9; the job is not SUCCEEDED yet, so no one
  // reads it meanwhile), to be made durable by SyncResult, e.g. while the SUCCEEDED state
  // is made durable; else atomically and durably (temp file, rename: three fsyncs).
  absl::Status PutResult(const std::string& job_id, std::string_view file, bool prepared);
  // fsyncs the job's result file (see PutResult).
  absl::Status SyncResult(const std::string& job_id);
  // The job's result file, verified: NOT_FOUND (lost) or DATA_LOSS (corrupt) with a message
  // naming the job, not the server's paths (the log names the file).
  absl::StatusOr<std::string> GetResult(const std::string& job_id);
  // Deletes a job's result file and solver checkpoint (a result found missing or corrupt
  // at a restart, before the job computes it again).
  void DiscardResult(const std::string& job_id);
  // Deletes the row blocks, checkpoint and other work files of a job (after it finished or
  // was cancelled); a written result is kept, an empty one from PrepareResult is not.
  void RemoveWorkFiles(const std::string& job_id);
  // The directory of a job's work files (removed with them: a file left in it goes too).
  std::string JobDir(const std::string& job_id) const;
  const std::string& data_dir() const { return data_dir_; }

 private:
  std::string ResultPath(const std::string& job_id) const;  // JobDir/result.rfb
  // A bundle stored under `base` (+ .files.rfb: paths and sizes, + .bundle.rfb: the bytes).
  static absl::StatusOr<StoredScene> GetBundle(const std::string& base, const std::string& name);
  // A scene's files under `base` (scenes/<sha256>), whichever form it was stored in.
  static absl::StatusOr<StoredScene> ReadSceneFiles(const std::string& base,
                                                    const std::string& name);
  explicit JobStore(std::string data_dir) : data_dir_(std::move(data_dir)) {}
  absl::StatusOr<std::optional<v1::Job>> FindRequestLocked(const std::string& owner,
                                                           const std::string& request_id,
                                                           const std::string& request_hash);
  absl::Status UpdateJobLocked(const v1::Job& job, bool sync);
  absl::StatusOr<std::vector<v1::Job>> QueryJobs(const std::string& sql,
                                                 const std::vector<std::string>& args);

  std::string data_dir_;
  std::mutex mu_;  // guards db_
  sqlite3* db_ = nullptr;
  SpaceReserve reserve_{data_dir_ + "/space_reserve"};  // guarded by mu_
  std::atomic<uint64_t> unsynced_commits_{0};  // Create/UpdateJob(sync = false) commits
  std::atomic<uint64_t> synced_commits_{0};    // how many of those are known durable
  std::mutex sync_mu_;                         // one SyncCommits at a time (not mu_)
  bool log_dir_synced_ = false;                // the log's directory entry, once per process
};

}  // namespace radflux
