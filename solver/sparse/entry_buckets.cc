#include "solver/sparse/entry_buckets.h"

#include <algorithm>

namespace radflux {

static_assert(sizeof(BucketEntry) == 12);

EntryBuckets::EntryBuckets(std::string directory, size_t buckets, size_t buffer_entries)
    : file_(std::move(directory), "pairs"),
      buffer_entries_(std::max<size_t>(1, buffer_entries)),
      buffers_(buckets),
      pieces_(buckets) {}

absl::Status EntryBuckets::Add(size_t bucket, const BucketEntry& entry) {
  std::vector<BucketEntry>& buffer = buffers_[bucket];
  if (buffer.capacity() == 0) buffer.reserve(buffer_entries_);
  buffer.push_back(entry);
  return buffer.size() == buffer_entries_ ? Write(bucket) : absl::OkStatus();
}

absl::Status EntryBuckets::Write(size_t bucket) {
  std::vector<BucketEntry>& buffer = buffers_[bucket];
  if (buffer.empty()) return absl::OkStatus();
  absl::StatusOr<uint64_t> offset =
      file_.Append(buffer.data(), buffer.size() * sizeof(BucketEntry));
  if (!offset.ok()) return offset.status();
  pieces_[bucket].emplace_back(*offset, buffer.size());
  buffer.clear();
  return absl::OkStatus();
}

absl::Status EntryBuckets::Finish() {
  for (size_t b = 0; b < buffers_.size(); ++b) {
    if (absl::Status s = Write(b); !s.ok()) return s;
    buffers_[b] = {};
  }
  return absl::OkStatus();
}

absl::Status EntryBuckets::Read(size_t bucket,
                                const std::function<void(std::span<const BucketEntry>)>& fn) const {
  for (const auto& [offset, entries] : pieces_[bucket]) {
    read_buffer_.resize(entries);
    const size_t bytes = entries * sizeof(BucketEntry);
    if (absl::Status s = file_.Read(offset, read_buffer_.data(), bytes); !s.ok()) return s;
    bytes_read_ += bytes;
    fn(read_buffer_);
  }
  return absl::OkStatus();
}

}  // namespace radflux
