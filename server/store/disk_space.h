// What a full disk means to the job store: a failed write becomes one plain status naming
// what was written and where ("disk full writing row blocks at PATH: No space left on
// device", RESOURCE_EXHAUSTED; any other error INTERNAL, "cannot write ..."), and a space
// reserve, a file of kReserveBytes in the data directory, is given back to the filesystem
// when the store must record that a job failed on a full disk, so that the FAILED state can
// always be written (and the job is not re-run into the same wall at every restart).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"

namespace radflux {

// The status of a write of `what` at `path` that failed with `error_number` (an errno):
// RESOURCE_EXHAUSTED "disk full writing WHAT at PATH: ..." for ENOSPC and EDQUOT, else
// INTERNAL "cannot write WHAT at PATH: ...". 0 (a short write with no errno) says so.
absl::Status DiskWriteError(std::string_view what, const std::string& path, int error_number);

// Bytes an unprivileged writer may still use on the filesystem of `dir` (statvfs).
absl::StatusOr<uint64_t> FreeDiskBytes(const std::string& dir);

// Bytes of the files under `dir`, recursively (0 for a directory that is not there; what
// cannot be read counts nothing).
uint64_t DirectoryBytes(const std::string& dir);

// True when `status` is a full disk (RESOURCE_EXHAUSTED from DiskWriteError or SQLite).
bool IsDiskFull(const absl::Status& status);

// The space reserve of a data directory. Not thread-safe (JobStore guards it).
class SpaceReserve {
 public:
  // Bytes kept back: enough for SQLite to record the end of every running job.
  static constexpr uint64_t kReserveBytes = 1u << 20;

  explicit SpaceReserve(std::string path) : path_(std::move(path)) {}
  // Creates the reserve file with its blocks allocated (posix_fallocate), if it is not
  // there already; RESOURCE_EXHAUSTED "disk full ..." when the disk cannot hold it.
  absl::Status Ensure();
  // Deletes the reserve file, giving its space back; true when there was one.
  bool Release();

 private:
  const std::string path_;
  bool held_ = false;  // the file exists with its blocks allocated
};

}  // namespace radflux
