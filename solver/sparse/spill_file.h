// SpillFile: one scratch file for data that does not fit in memory, appended to and read back
// at offsets. Created on the first Append in `directory` ("" = a fresh radflux-spill-XXXXXX
// under $TMPDIR or /tmp, removed by the destructor) and unlinked as soon as it is created, so
// it disappears when the SpillFile is destroyed or the process dies. Every error names the
// file and what failed: RESOURCE_EXHAUSTED "... (disk full)" when the disk is full,
// DATA_LOSS for other IO errors, FAILED_PRECONDITION when the file cannot be created.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace radflux {

class SpillFile {
 public:
  // `name`: the file's name before its random part (e.g. "rows" for rows-XXXXXX.spill).
  SpillFile(std::string directory, std::string name);
  ~SpillFile();
  SpillFile(const SpillFile&) = delete;
  SpillFile& operator=(const SpillFile&) = delete;

  // Writes `bytes` bytes at the end of the file; returns the offset they start at.
  absl::StatusOr<uint64_t> Append(const void* data, size_t bytes);
  // Reads `bytes` bytes at `offset` (written before) into `data`.
  absl::Status Read(uint64_t offset, void* data, size_t bytes) const;
  uint64_t size() const { return end_; }
  // The file's path while open ("" before the first Append); it is already unlinked.
  const std::string& path() const { return path_; }

 private:
  absl::Status Open();

  std::string directory_, name_;
  std::string owned_directory_;  // created by us, removed by the destructor
  std::string path_;
  int fd_ = -1;
  uint64_t end_ = 0;
};

}  // namespace radflux
