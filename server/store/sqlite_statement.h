// The job store's SQLite helpers, shared by its files (job_store.cc, scene_store.cc,
// store_schema.cc): a self-finalizing prepared statement, commits without their fsync, and
// the status of a failed statement.
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace radflux::store_sql {

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
inline absl::Status SqlError(sqlite3* db, std::string_view what) {
  if ((sqlite3_errcode(db) & 0xff) == SQLITE_FULL) {
    return absl::ResourceExhaustedError(absl::StrCat("disk full writing ", std::string(what), " at ",
                                                     sqlite3_db_filename(db, "main"), ": ",
                                                     sqlite3_errmsg(db)));
  }
  return absl::InternalError(
      absl::StrCat("job store: ", std::string(what), ": ", sqlite3_errmsg(db)));
}

}  // namespace radflux::store_sql
