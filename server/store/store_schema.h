// The job store's SQLite schema and its migrations: a database of any earlier version is
// brought to the current one when the store opens (PRAGMA user_version counts them).
#pragma once

#include "absl/status/status.h"

struct sqlite3;

namespace radflux {

// Creates the tables of a new database, or migrates an older one, in one transaction per
// version (a failed migration leaves the database as it was):
//   1: jobs and scenes belong to principals: jobs.owner, scene_owners; request ids are
//      unique per owner and carry the SubmitRequestHash of their request. Rows stored
//      before belong to the "default" principal.
absl::Status MigrateStoreSchema(sqlite3* db);

}  // namespace radflux
