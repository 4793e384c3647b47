// EntryBuckets: (row, col, value) entries sorted on disk into buckets, then read back bucket by
// bucket, each bucket's entries in the order they were added: the external half of a
// transpose (reciprocal_pairs.h gathers each row range's column entries this way). Each bucket
// buffers up to `buffer_entries` entries in memory and appends them to one SpillFile
// (spill_file.h) when the buffer fills. Memory: buckets x buffer_entries x 12 bytes at most;
// disk: every entry is written once and read once per Read of its bucket, 12 bytes each way.
// Errors (disk full, IO) name the file (spill_file.h).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "solver/sparse/spill_file.h"

namespace radflux {

struct BucketEntry {
  uint32_t row = 0, col = 0;
  float value = 0;
};

class EntryBuckets {
 public:
  // `directory`: where the file goes, as SpillFile; nothing is created before a buffer fills.
  EntryBuckets(std::string directory, size_t buckets, size_t buffer_entries);

  absl::Status Add(size_t bucket, const BucketEntry& entry);
  // Writes the buffers still holding entries and frees them: once, after the last Add.
  absl::Status Finish();
  // Calls fn on bucket `bucket`'s entries in the order added, a written piece at a time.
  absl::Status Read(size_t bucket,
                    const std::function<void(std::span<const BucketEntry>)>& fn) const;

  uint64_t BytesWritten() const { return file_.size(); }
  uint64_t BytesRead() const { return bytes_read_; }

 private:
  absl::Status Write(size_t bucket);

  SpillFile file_;
  size_t buffer_entries_;
  std::vector<std::vector<BucketEntry>> buffers_;
  std::vector<std::vector<std::pair<uint64_t, size_t>>> pieces_;  // per bucket: offset, entries
  mutable std::vector<BucketEntry> read_buffer_;
  mutable uint64_t bytes_read_ = 0;
};

}  // namespace radflux
