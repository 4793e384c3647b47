#include "server/store/job_store.h"

#include <sqlite3.h>

#include <filesystem>
#include <map>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "server/store/blob_file.h"
#include "server/store/disk_space.h"
#include "wire/proto_convert.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSchema = R"sql(
PRAGMA journal_mode=WAL;
PRAGMA synchronous=FULL;
CREATE TABLE IF NOT EXISTS scenes(
  sha256 TEXT PRIMARY KEY, name TEXT NOT NULL, created_ms INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS jobs(
  seq INTEGER PRIMARY KEY AUTOINCREMENT, job_id TEXT UNIQUE NOT NULL,
  request_id TEXT UNIQUE, scene_sha256 TEXT NOT NULL, state INTEGER NOT NULL,
  job BLOB NOT NULL);
CREATE TABLE IF NOT EXISTS job_histories(
  job_id TEXT PRIMARY KEY, rebuilds INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS durable_results(job_id TEXT PRIMARY KEY);
)sql";

// A prepared statement that finalizes itself.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) {
    status_ = sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr);
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  bool ok() const { return status_ == SQLITE_OK; }
  void Bind(int i, const std::string& text) {
    sqlite3_bind_text(stmt_, i, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
  }
  void BindBlob(int i, const std::string& bytes) {
    sqlite3_bind_blob(stmt_, i, bytes.data(), static_cast<int>(bytes.size()), SQLITE_TRANSIENT);
  }
  void BindInt(int i, int64_t v) { sqlite3_bind_int64(stmt_, i, v); }
  void BindNull(int i) { sqlite3_bind_null(stmt_, i); }
  int Step() { return sqlite3_step(stmt_); }
  int64_t ColumnInt(int i) { return sqlite3_column_int64(stmt_, i); }
  std::string Column(int i) {
    const void* data = sqlite3_column_blob(stmt_, i);
    return std::string(static_cast<const char*>(data),
                       static_cast<size_t>(sqlite3_column_bytes(stmt_, i)));
  }

 private:
  sqlite3_stmt* stmt_ = nullptr;
  int status_ = SQLITE_ERROR;
};

// While it lives (and `active`), the connection's commits skip their own fsync
// (synchronous=NORMAL: they survive kill -9, not an OS crash); then FULL again, the store's
// default. Held under the store's lock.
class CommitsWithoutFsync {
 public:
  CommitsWithoutFsync(sqlite3* db, bool active) : db_(active ? db : nullptr) {
    if (db_ != nullptr) sqlite3_exec(db_, "PRAGMA synchronous=NORMAL", nullptr, nullptr, nullptr);
  }
  ~CommitsWithoutFsync() {
    if (db_ != nullptr) sqlite3_exec(db_, "PRAGMA synchronous=FULL", nullptr, nullptr, nullptr);
  }
  CommitsWithoutFsync(const CommitsWithoutFsync&) = delete;
  CommitsWithoutFsync& operator=(const CommitsWithoutFsync&) = delete;

 private:
  sqlite3* const db_;
};

// A failed statement; a full disk as DiskWriteError says it ("disk full writing WHAT at
// the database's path: ...").
absl::Status SqlError(sqlite3* db, std::string_view what) {
  if ((sqlite3_errcode(db) & 0xff) == SQLITE_FULL) {
    return absl::ResourceExhaustedError(absl::StrCat("disk full writing ", std::string(what), " at ",
                                                     sqlite3_db_filename(db, "main"), ": ",
                                                     sqlite3_errmsg(db)));
  }
  return absl::InternalError(
      absl::StrCat("job store: ", std::string(what), ": ", sqlite3_errmsg(db)));
}

std::string RowBlockName(uint32_t index) { return absl::StrCat("rows_", index, ".rfb"); }

}  // namespace

absl::StatusOr<std::unique_ptr<JobStore>> JobStore::Open(const std::string& data_dir) {
  std::error_code ec;
  fs::create_directories(fs::path(data_dir) / "scenes", ec);
  fs::create_directories(fs::path(data_dir) / "jobs", ec);
  if (ec) return absl::InternalError(absl::StrCat("cannot create ", data_dir, ": ", ec.message()));
  std::unique_ptr<JobStore> store(new JobStore(data_dir));
  const std::string db_path = (fs::path(data_dir) / "radflux.db").string();
  if (sqlite3_open(db_path.c_str(), &store->db_) != SQLITE_OK) {
    return SqlError(store->db_, absl::StrCat("cannot open ", db_path));
  }
  sqlite3_busy_timeout(store->db_, 5000);
  if (absl::Status s = store->Exec(kSchema); !s.ok()) return s;
  (void)store->EnsureSpaceReserve();  // a full disk refuses submits, not the start
  return store;
}

JobStore::~JobStore() { sqlite3_close(db_); }

absl::Status JobStore::Exec(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    absl::Status s = absl::InternalError(absl::StrCat("job store: ", error ? error : "?"));
    sqlite3_free(error);
    return s;
  }
  return absl::OkStatus();
}

std::string JobStore::JobDir(const std::string& job_id) const {
  return (fs::path(data_dir_) / "jobs" / job_id).string();
}

std::string JobStore::ResultPath(const std::string& job_id) const {
  return (fs::path(JobDir(job_id)) / "result.rfb").string();
}

absl::Status JobStore::EnsureSpaceReserve() {
  std::lock_guard lock(mu_);
  return reserve_.Ensure();
}

bool JobStore::HasScene(const std::string& sha256) {
  std::lock_guard lock(mu_);
  Statement st(db_, "SELECT 1 FROM scenes WHERE sha256 = ?");
  st.Bind(1, sha256);
  return st.ok() && st.Step() == SQLITE_ROW;
}

absl::Status JobStore::PutScene(const std::string& sha256, const StoredScene& scene) {
  const std::string base = (fs::path(data_dir_) / "scenes" / sha256).string();
  const auto write = [&](const std::string& suffix, const std::string& text) {
    absl::Status s = WriteBlobFile(base + suffix, text, "a scene");
    if (!s.ok()) {  // no part of the scene stays behind
      std::error_code ec;
      for (const char* part : {".mesh.rfb", ".obj.rfb", ".mtl.rfb", ".files.rfb", ".bundle.rfb"}) {
        fs::remove(base + part, ec);
      }
    }
    return s;
  };
  if (!scene.files.empty()) {
    v1::SceneHeader index;  // the files' paths and sizes; their bytes follow in .bundle.rfb
    std::string data;
    for (const BundleFile& file : scene.files) {
      v1::BundleFile* entry = index.add_files();
      entry->set_path(file.path);
      entry->set_size(file.data.size());
      data += file.data;
    }
    if (absl::Status s = write(".files.rfb", index.SerializeAsString()); !s.ok()) return s;
    if (absl::Status s = write(".bundle.rfb", data); !s.ok()) return s;
  } else if (!scene.mesh.empty()) {
    if (absl::Status s = write(".mesh.rfb", scene.mesh); !s.ok()) return s;
  } else {
    if (absl::Status s = write(".obj.rfb", scene.obj); !s.ok()) return s;
    if (absl::Status s = write(".mtl.rfb", scene.mtl); !s.ok()) return s;
  }
  std::lock_guard lock(mu_);
  Statement st(db_,
               "INSERT OR IGNORE INTO scenes(sha256, name, created_ms) VALUES(?, ?, "
               "CAST((julianday('now') - 2440587.5) * 86400000 AS INTEGER))");
  st.Bind(1, sha256);
  st.Bind(2, scene.name);
  if (!st.ok() || st.Step() != SQLITE_DONE) return SqlError(db_, "a scene");
  return absl::OkStatus();
}

absl::StatusOr<StoredScene> JobStore::GetBundle(const std::string& base, const std::string& name) {
  absl::StatusOr<std::string> index = ReadBlobFile(base + ".files.rfb");
  if (!index.ok()) return index.status();
  absl::StatusOr<std::string> data = ReadBlobFile(base + ".bundle.rfb");
  if (!data.ok()) return data.status();
  v1::SceneHeader header;
  if (!header.ParseFromString(*index)) return absl::DataLossError(base + ".files.rfb: corrupt");
  header.set_name(name);
  return SplitScenePayload(header, *data);
}

absl::StatusOr<StoredScene> JobStore::GetScene(const std::string& sha256) {
  StoredScene scene;
  {
    std::lock_guard lock(mu_);
    Statement st(db_, "SELECT name FROM scenes WHERE sha256 = ?");
    st.Bind(1, sha256);
    if (!st.ok() || st.Step() != SQLITE_ROW) {
      return absl::NotFoundError(
          absl::StrCat("no scene with sha256 ", sha256, "; upload it first"));
    }
    scene.name = st.Column(0);
  }
  const std::string base = (fs::path(data_dir_) / "scenes" / sha256).string();
  if (std::error_code ec; fs::exists(base + ".files.rfb", ec)) return GetBundle(base, scene.name);
  if (std::error_code ec; fs::exists(base + ".mesh.rfb", ec)) {
    absl::StatusOr<std::string> mesh = ReadBlobFile(base + ".mesh.rfb");
    if (!mesh.ok()) return mesh.status();
    scene.mesh = *std::move(mesh);
    return scene;
  }
  absl::StatusOr<std::string> obj = ReadBlobFile(base + ".obj.rfb");
  if (!obj.ok()) return obj.status();
  absl::StatusOr<std::string> mtl = ReadBlobFile(base + ".mtl.rfb");
  if (!mtl.ok()) return mtl.status();
  scene.obj = *std::move(obj);
  scene.mtl = *std::move(mtl);
  return scene;
}

absl::StatusOr<v1::Job> JobStore::CreateJob(const v1::Job& job, bool sync) {
  std::lock_guard lock(mu_);
  if (!job.request_id().empty()) {
    Statement find(db_, "SELECT job FROM jobs WHERE request_id = ?");
    find.Bind(1, job.request_id());
    if (find.ok() && find.Step() == SQLITE_ROW) {
      v1::Job existing;
      if (!existing.ParseFromString(find.Column(0))) return absl::DataLossError("corrupt job row");
      return existing;
    }
  }
  absl::Status inserted;
  {
    const CommitsWithoutFsync unsynced(db_, !sync);
    Statement st(db_,
                 "INSERT INTO jobs(job_id, request_id, scene_sha256, state, job) "
                 "VALUES(?, ?, ?, ?, ?)");
    st.Bind(1, job.job_id());
    if (job.request_id().empty())
      st.BindNull(2);
    else
      st.Bind(2, job.request_id());
    st.Bind(3, job.scene_sha256());
    st.BindInt(4, job.state());
    st.BindBlob(5, job.SerializeAsString());
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
  }
  return jobs;
}

absl::StatusOr<v1::Job> JobStore::GetJob(const std::string& job_id) {
  absl::StatusOr<std::vector<v1::Job>> jobs =
      QueryJobs("SELECT job FROM jobs WHERE job_id = ?", {job_id});
  if (!jobs.ok()) return jobs.status();
  if (jobs->empty()) return absl::NotFoundError(absl::StrCat("no job ", job_id));
  return jobs->front();
}

absl::StatusOr<v1::Job> JobStore::GetJobByRequestId(const std::string& request_id) {
  absl::StatusOr<std::vector<v1::Job>> jobs =
      QueryJobs("SELECT job FROM jobs WHERE request_id = ?", {request_id});
  if (!jobs.ok()) return jobs.status();
  if (jobs->empty()) return absl::NotFoundError(absl::StrCat("no job for request ", request_id));
  return jobs->front();
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
  const std::string sql = absl::StrCat("SELECT job FROM jobs", where.empty() ? "" : " WHERE ",
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
      absl::StrCat("SELECT job FROM jobs WHERE state IN (", static_cast<int>(v1::JOB_STATE_QUEUED),
                   ",", static_cast<int>(v1::JOB_STATE_RUNNING), ") ORDER BY seq ASC"),
      {});
}

absl::StatusOr<std::vector<v1::Job>> JobStore::UncheckedResults() {
  return QueryJobs(
      absl::StrCat("SELECT job FROM jobs WHERE state = ", static_cast<int>(v1::JOB_STATE_SUCCEEDED),
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

absl::Status JobStore::PutRowBlocks(const std::string& job_id, uint32_t name_index,
                                    const std::vector<const StoredRowBlock*>& blocks) {
  return WriteBlobFile((fs::path(JobDir(job_id)) / RowBlockName(name_index)).string(),
                       EncodeRowBlockGroup(blocks), "row blocks");
}

void JobStore::ForEachRowBlock(const std::string& job_id,
                               const std::function<void(StoredRowBlock)>& fn,
                               std::vector<absl::Status>* unreadable) {
  std::map<uint32_t, fs::path> files;  // by the index in their name
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(JobDir(job_id), ec)) {
    const std::string name = entry.path().stem().string();
    uint32_t index = 0;
    if (name.rfind("rows_", 0) != 0 || entry.path().extension() != ".rfb" ||
        !absl::SimpleAtoi(name.substr(5), &index)) {
      continue;
    }
    files.emplace(index, entry.path());
  }
  for (const auto& [index, path] : files) {
    absl::StatusOr<std::string> bytes = ReadBlobFile(path.string());
    absl::StatusOr<std::vector<StoredRowBlock>> group =
        bytes.ok() ? DecodeRowBlockGroup(*bytes) : bytes.status();
    if (!group.ok()) {
      unreadable->push_back(
          absl::DataLossError(absl::StrCat(path.string(), ": ", group.status().message())));
      continue;
    }
    for (StoredRowBlock& block : *group) fn(std::move(block));
  }
}

absl::Status JobStore::PutCheckpoint(const std::string& job_id, const SolverCheckpoint& c) {
  return WriteBlobFile((fs::path(JobDir(job_id)) / "checkpoint.rfb").string(), EncodeCheckpoint(c),
                       "a solver checkpoint");
}

absl::StatusOr<SolverCheckpoint> JobStore::GetCheckpoint(const std::string& job_id) {
  absl::StatusOr<std::string> bytes =
      ReadBlobFile((fs::path(JobDir(job_id)) / "checkpoint.rfb").string());
  if (!bytes.ok()) return bytes.status();
  return DecodeCheckpoint(*bytes);
}

absl::Status JobStore::PrepareResult(const std::string& job_id) {
  std::error_code ec;
  fs::create_directories(JobDir(job_id), ec);
  if (ec) return absl::InternalError(absl::StrCat("cannot create ", JobDir(job_id)));
  return CreateDurableFile(ResultPath(job_id));
}

absl::Status JobStore::PutResult(const std::string& job_id, std::string_view file, bool prepared) {
  const std::string path = ResultPath(job_id);
  absl::Status s = prepared ? WriteBuiltBlobFileInPlace(path, file, "the result")
                            : WriteBuiltBlobFile(path, file, "the result");
  std::error_code ec;
  if (!s.ok()) fs::remove(path, ec);  // a part of a result is no result
  return s;
}

absl::Status JobStore::SyncResult(const std::string& job_id) {
  const std::string path = ResultPath(job_id);
  if (!SyncPath(path)) return absl::InternalError(absl::StrCat("cannot fsync ", path));
  return absl::OkStatus();
}

absl::StatusOr<std::string> JobStore::GetResult(const std::string& job_id) {
  return ReadBlobFile(ResultPath(job_id));
}

void JobStore::DiscardResult(const std::string& job_id) {
  std::error_code ec;
  fs::remove(ResultPath(job_id), ec);
  fs::remove(fs::path(JobDir(job_id)) / "checkpoint.rfb", ec);
}

void JobStore::RemoveWorkFiles(const std::string& job_id) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(JobDir(job_id), ec)) {
    const bool result = entry.path().filename() == "result.rfb" && entry.file_size(ec) > 0;
    if (!result) fs::remove(entry.path(), ec);
  }
}

}  // namespace radflux
