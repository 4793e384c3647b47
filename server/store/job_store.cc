#include "server/store/job_store.h"

#include <sqlite3.h>

#include <filesystem>
#include <optional>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "server/store/blob_file.h"
#include "server/store/disk_space.h"
#include "server/store/sqlite_statement.h"
#include "server/store/store_schema.h"
#include "wire/proto_convert.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;
using store_sql::CommitsWithoutFsync;
using store_sql::SqlError;
using store_sql::Statement;

// The columns QueryJobs reads.
constexpr const char* kSelectJobs = "SELECT job, owner FROM jobs";

// FAILED_PRECONDITION when `data_dir` holds scene or job files but not `db_path`: a store
// whose database was lost, which an empty new database would silently orphan.
absl::Status CheckDatabaseNotLost(const std::string& data_dir, const std::string& db_path) {
  std::error_code ec;
  if (fs::exists(db_path, ec)) return absl::OkStatus();
  for (const char* part : {"scenes", "jobs"}) {
    const fs::path dir = fs::path(data_dir) / part;
    if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec)) {
      return absl::FailedPreconditionError(absl::StrCat(
          data_dir, " holds stored ", part, " but no database (", db_path,
          "): restore radflux.db from a backup, or move ", data_dir,
          " away and start with an empty --data-dir"));
    }
  }
  return absl::OkStatus();
}

// Removes the temp files of uploads a crash cut short (StreamedBlobFile's "upload.*").
void RemoveCutUploads(const fs::path& scenes) {
  std::error_code ec;
  for (fs::directory_iterator it(scenes, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().starts_with("upload.")) fs::remove(it->path(), ec);
  }
}

}  // namespace

absl::StatusOr<std::unique_ptr<JobStore>> JobStore::Open(const std::string& data_dir) {
  const std::string db_path = (fs::path(data_dir) / "radflux.db").string();
  if (absl::Status s = CheckDatabaseNotLost(data_dir, db_path); !s.ok()) return s;
  std::error_code ec;
  fs::create_directories(fs::path(data_dir) / "scenes", ec);
  fs::create_directories(fs::path(data_dir) / "jobs", ec);
  if (ec) return absl::InternalError(absl::StrCat("cannot create ", data_dir, ": ", ec.message()));
  RemoveCutUploads(fs::path(data_dir) / "scenes");
  std::unique_ptr<JobStore> store(new JobStore(data_dir));
  if (sqlite3_open(db_path.c_str(), &store->db_) != SQLITE_OK) {
    return SqlError(store->db_, absl::StrCat("cannot open ", db_path));
  }
  sqlite3_busy_timeout(store->db_, 5000);
  if (absl::Status s = MigrateStoreSchema(store->db_); !s.ok()) return s;
  (void)store->EnsureSpaceReserve();  // a full disk refuses submits, not the start
  return store;
}

JobStore::~JobStore() { sqlite3_close(db_); }

std::string JobStore::JobDir(const std::string& job_id) const {
  return (fs::path(data_dir_) / "jobs" / job_id).string();
}

absl::Status JobStore::EnsureSpaceReserve() {
  std::lock_guard lock(mu_);
  return reserve_.Ensure();
}

absl::StatusOr<std::optional<v1::Job>> JobStore::FindRequestLocked(
    const std::string& owner, const std::string& request_id, const std::string& request_hash) {
  if (request_id.empty()) return std::nullopt;
  Statement find(db_, "SELECT job, request_hash FROM jobs WHERE owner = ? AND request_id = ?");
  find.Bind(1, owner);
  find.Bind(2, request_id);
  if (!find.ok()) return SqlError(db_, "find a request");
  if (find.Step() != SQLITE_ROW) return std::nullopt;
  v1::Job earlier;
  if (!earlier.ParseFromString(find.Column(0))) return absl::DataLossError("corrupt job row");
  if (find.Column(1) == request_hash) {
    earlier.set_owner(owner);
    return earlier;
  }
  return absl::FailedPreconditionError(absl::StrCat(
      "request_id \"", request_id, "\" was used for another request (job ", earlier.job_id(),
      ": scene ", earlier.scene_sha256().substr(0, 12), " with its options); a new request "
      "needs a new request_id"));
}

absl::StatusOr<std::optional<v1::Job>> JobStore::FindRequest(const std::string& owner,
                                                             const std::string& request_id,
                                                             const std::string& request_hash) {
  std::lock_guard lock(mu_);
  return FindRequestLocked(owner, request_id, request_hash);
}

absl::StatusOr<v1::Job> JobStore::CreateJob(const v1::Job& job, const std::string& request_hash,
                                            bool sync) {
  std::lock_guard lock(mu_);
  absl::StatusOr<std::optional<v1::Job>> earlier =
      FindRequestLocked(job.owner(), job.request_id(), request_hash);
  if (!earlier.ok()) return earlier.status();
  if (earlier->has_value()) return **earlier;
  absl::Status inserted;
  {
    const CommitsWithoutFsync unsynced(db_, !sync);
    Statement st(db_,
                 "INSERT INTO jobs(job_id, owner, request_id, request_hash, scene_sha256, state, "
                 "job) VALUES(?, ?, ?, ?, ?, ?, ?)");
    st.Bind(1, job.job_id());
    st.Bind(2, job.owner());
    if (job.request_id().empty()) {
      st.BindNull(3);
      st.BindNull(4);
    } else {
      st.Bind(3, job.request_id());
      st.Bind(4, request_hash);
    }
    st.Bind(5, job.scene_sha256());
    st.BindInt(6, job.state());
    st.BindBlob(7, job.SerializeAsString());
    if (!st.ok() || st.Step() != SQLITE_DONE) inserted = SqlError(db_, "a new job");
  }
  if (!inserted.ok()) return inserted;
  if (!sync) ++unsynced_commits_;
  std::error_code ec;
  fs::create_directories(JobDir(job.job_id()), ec);
  return job;
}

absl::Status JobStore::SyncCommits() {
  const uint64_t target = unsynced_commits_.load();
  if (synced_commits_.load() >= target) return absl::OkStatus();
  std::lock_guard lock(sync_mu_);
  if (synced_commits_.load() >= target) return absl::OkStatus();  // a sync just covered it
  // The log lives as long as the connection; its name is made durable once per process (a
  // fresh log's first synchronous=FULL commit would do the same).
  const std::string log = (fs::path(data_dir_) / "radflux.db-wal").string();
  if (!SyncPath(log) || (!log_dir_synced_ && !SyncPath(data_dir_))) {
    return absl::InternalError(absl::StrCat("job store: cannot fsync ", log));
  }
  log_dir_synced_ = true;
  synced_commits_.store(target);
  return absl::OkStatus();
}

absl::Status JobStore::UpdateJob(const v1::Job& job, bool sync) {
  std::lock_guard lock(mu_);
  absl::Status status = UpdateJobLocked(job, sync);
  // The end of a job is always recorded: on a full disk, with the space kept for it.
  if (IsDiskFull(status) && IsTerminal(job.state()) && reserve_.Release()) {
    status = UpdateJobLocked(job, sync);
  }
  return status;
}

absl::Status JobStore::UpdateJobLocked(const v1::Job& job, bool sync) {
  // A RUNNING job's phase is not fsynced (synchronous=NORMAL: it survives kill -9, an OS
  // crash may lose it, and the job resumes from its files either way); every other state
  // is, with whatever was committed before it, here or (sync = false) in SyncCommits.
  const bool running = job.state() == v1::JOB_STATE_RUNNING;
  const bool deferred = !running && !sync;
  absl::Status status;
  {
    const CommitsWithoutFsync unsynced(db_, running || deferred);
    Statement st(db_, "UPDATE jobs SET state = ?, job = ? WHERE job_id = ?");
    st.BindInt(1, job.state());
    st.BindBlob(2, job.SerializeAsString());
    st.Bind(3, job.job_id());
    if (!st.ok() || st.Step() != SQLITE_DONE) status = SqlError(db_, "the job's state");
  }
  if (deferred && status.ok()) ++unsynced_commits_;
  return status;
}

absl::StatusOr<std::vector<v1::Job>> JobStore::QueryJobs(const std::string& sql,
                                                         const std::vector<std::string>& args) {
  std::lock_guard lock(mu_);
  Statement st(db_, sql);
  if (!st.ok()) return SqlError(db_, "query jobs");
  for (size_t i = 0; i < args.size(); ++i) st.Bind(static_cast<int>(i + 1), args[i]);
  std::vector<v1::Job> jobs;
  while (st.Step() == SQLITE_ROW) {
    if (!jobs.emplace_back().ParseFromString(st.Column(0))) {
      return absl::DataLossError("corrupt job row");
    }
    jobs.back().set_owner(st.Column(1));  // rows from before owners have it only here
  }
  return jobs;
}

absl::StatusOr<v1::Job> JobStore::GetJob(const std::string& job_id) {
  absl::StatusOr<std::vector<v1::Job>> jobs =
      QueryJobs(absl::StrCat(kSelectJobs, " WHERE job_id = ?"), {job_id});
  if (!jobs.ok()) return jobs.status();
  if (jobs->empty()) return absl::NotFoundError(absl::StrCat("no job ", job_id));
  return jobs->front();
}

absl::StatusOr<int64_t> JobStore::CountUnfinishedJobs(const std::string& owner) {
  std::lock_guard lock(mu_);
  Statement st(db_, absl::StrCat("SELECT COUNT(*) FROM jobs WHERE owner = ? AND state IN (",
                                 static_cast<int>(v1::JOB_STATE_QUEUED), ",",
                                 static_cast<int>(v1::JOB_STATE_RUNNING), ")"));
  st.Bind(1, owner);
  if (!st.ok() || st.Step() != SQLITE_ROW) return SqlError(db_, "count unfinished jobs");
  return st.ColumnInt(0);
}

absl::StatusOr<std::vector<v1::Job>> JobStore::ListJobs(const JobFilter& filter) {
  std::vector<std::string> where;
  std::vector<std::string> args;
  if (!filter.states.empty()) {
    std::vector<std::string> states;
    for (v1::JobState s : filter.states) states.push_back(std::to_string(static_cast<int>(s)));
    where.push_back(absl::StrCat("state IN (", absl::StrJoin(states, ","), ")"));
  }
  if (!filter.scene_sha256.empty()) {
    where.push_back("scene_sha256 = ?");
    args.push_back(filter.scene_sha256);
  }
  if (!filter.owner.empty()) {
    where.push_back("owner = ?");
    args.push_back(filter.owner);
  }
  const std::string sql = absl::StrCat(kSelectJobs, where.empty() ? "" : " WHERE ",
                                       absl::StrJoin(where, " AND "), " ORDER BY seq DESC LIMIT ",
                                       filter.limit, " OFFSET ", filter.offset);
  return QueryJobs(sql, args);
}

absl::StatusOr<uint64_t> JobStore::NextHistoryBase(const std::string& job_id) {
  std::lock_guard lock(mu_);
  Statement st(db_,
               "INSERT INTO job_histories(job_id, rebuilds) VALUES(?, 1) "
               "ON CONFLICT(job_id) DO UPDATE SET rebuilds = rebuilds + 1 RETURNING rebuilds");
  st.Bind(1, job_id);
  if (!st.ok() || st.Step() != SQLITE_ROW) return SqlError(db_, "next history base");
  return static_cast<uint64_t>(st.ColumnInt(0)) << kHistorySequenceBits;
}

absl::StatusOr<std::vector<v1::Job>> JobStore::UnfinishedJobs() {
  return QueryJobs(
      absl::StrCat(kSelectJobs, " WHERE state IN (", static_cast<int>(v1::JOB_STATE_QUEUED),
                   ",", static_cast<int>(v1::JOB_STATE_RUNNING), ") ORDER BY seq ASC"),
      {});
}

absl::StatusOr<std::vector<v1::Job>> JobStore::UncheckedResults() {
  return QueryJobs(
      absl::StrCat(kSelectJobs, " WHERE state = ", static_cast<int>(v1::JOB_STATE_SUCCEEDED),
                   " AND job_id NOT IN (SELECT job_id FROM durable_results)"
                   " ORDER BY seq ASC"),
      {});
}

absl::Status JobStore::MarkResultDurable(const std::string& job_id) {
  std::lock_guard lock(mu_);
  const CommitsWithoutFsync unsynced(db_, true);
  Statement st(db_, "INSERT OR IGNORE INTO durable_results(job_id) VALUES(?)");
  st.Bind(1, job_id);
  if (!st.ok() || st.Step() != SQLITE_DONE) return SqlError(db_, "mark result durable");
  return absl::OkStatus();
}

}  // namespace radflux
