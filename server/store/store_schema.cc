#include "server/store/store_schema.h"

#include <iterator>
#include <vector>

#include "server/jobs/principal.h"
#include "server/store/request_hash.h"
#include "server/store/sqlite_statement.h"

namespace radflux {
namespace {

using store_sql::SqlError;
using store_sql::Statement;

// Version 0: the tables as first written (a new database starts here too).
constexpr const char* kSchemaV0 = R"sql(
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

// Version 1: owners (the rows so far are kDefaultPrincipal's), request ids per owner.
constexpr const char* kMigrationV1 = R"sql(
CREATE TABLE jobs_v1(
  seq INTEGER PRIMARY KEY AUTOINCREMENT, job_id TEXT UNIQUE NOT NULL, owner TEXT NOT NULL,
  request_id TEXT, request_hash TEXT, scene_sha256 TEXT NOT NULL, state INTEGER NOT NULL,
  job BLOB NOT NULL, UNIQUE(owner, request_id));
INSERT INTO jobs_v1(seq, job_id, owner, request_id, scene_sha256, state, job)
  SELECT seq, job_id, 'default', request_id, scene_sha256, state, job FROM jobs;
DROP TABLE jobs;
ALTER TABLE jobs_v1 RENAME TO jobs;
CREATE INDEX jobs_by_owner ON jobs(owner, seq);
CREATE TABLE scene_owners(sha256 TEXT NOT NULL, owner TEXT NOT NULL, PRIMARY KEY(sha256, owner));
INSERT INTO scene_owners(sha256, owner) SELECT sha256, 'default' FROM scenes;
)sql";

absl::Status Exec(sqlite3* db, const char* sql) {
  if (sqlite3_exec(db, sql, nullptr, nullptr, nullptr) != SQLITE_OK) return SqlError(db, sql);
  return absl::OkStatus();
}

// The request hash of every job that has a request id (version 0 stored none).
absl::Status HashStoredRequests(sqlite3* db) {
  std::vector<std::pair<int64_t, std::string>> hashes;
  {
    Statement st(db, "SELECT seq, job FROM jobs WHERE request_id IS NOT NULL");
    while (st.ok() && st.Step() == SQLITE_ROW) {
      v1::Job job;
      if (!job.ParseFromString(st.Column(1))) return absl::DataLossError("corrupt job row");
      hashes.emplace_back(st.ColumnInt(0), SubmitRequestHash(job.scene_sha256(), job.options()));
    }
  }
  for (const auto& [seq, hash] : hashes) {
    Statement st(db, "UPDATE jobs SET request_hash = ? WHERE seq = ?");
    st.Bind(1, hash);
    st.BindInt(2, seq);
    if (!st.ok() || st.Step() != SQLITE_DONE) return SqlError(db, "a request hash");
  }
  return absl::OkStatus();
}

absl::Status MigrateToV1(sqlite3* db) {
  if (absl::Status s = Exec(db, kMigrationV1); !s.ok()) return s;
  return HashStoredRequests(db);
}

}  // namespace

absl::Status MigrateStoreSchema(sqlite3* db) {
  if (absl::Status s = Exec(db, kSchemaV0); !s.ok()) return s;
  using Migration = absl::Status (*)(sqlite3*);
  constexpr Migration kMigrations[] = {MigrateToV1};  // [i] brings version i to i + 1
  int64_t version = 0;
  {
    Statement query(db, "PRAGMA user_version");
    if (!query.ok() || query.Step() != SQLITE_ROW) return SqlError(db, "the schema version");
    version = query.ColumnInt(0);
  }
  for (int64_t v = version; v < static_cast<int64_t>(std::size(kMigrations)); ++v) {
    if (absl::Status s = Exec(db, "BEGIN IMMEDIATE"); !s.ok()) return s;
    absl::Status s = kMigrations[v](db);
    if (s.ok()) s = Exec(db, absl::StrCat("PRAGMA user_version = ", v + 1).c_str());
    if (s.ok()) s = Exec(db, "COMMIT");
    if (!s.ok()) {
      sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
      return s;
    }
  }
  return absl::OkStatus();
}

}  // namespace radflux
