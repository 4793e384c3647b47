#include "solver/sparse/row_store.h"

#include <array>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "absl/strings/str_cat.h"
#include "solver/core/seconds_since.h"

namespace radflux {
namespace {

// Appends `block`'s rows to `chunk` (row offsets rebased).
void AppendRows(const RowBlock& block, RowBlock& chunk) {
  const uint64_t base = chunk.col.size();
  chunk.col.insert(chunk.col.end(), block.col.begin(), block.col.end());
  chunk.value.insert(chunk.value.end(), block.value.begin(), block.value.end());
  for (size_t r = 1; r < block.row_begin.size(); ++r) {
    chunk.row_begin.push_back(base + block.row_begin[r]);
  }
}

// A RowBlock with no rows starting at `first_row`.
RowBlock EmptyChunk(uint32_t first_row) {
  RowBlock chunk;
  chunk.first_row = first_row;
  return chunk;
}

}  // namespace

RowStore::RowStore(uint32_t cols, uint64_t memory_budget, std::unique_ptr<BlockSpill> spill,
                   uint64_t chunk_bytes)
    : cols_(cols), budget_(memory_budget), chunk_bytes_(chunk_bytes), spill_(std::move(spill)) {}

absl::Status RowStore::Append(RowBlock block) {
  if (block.first_row != rows_ || block.row_begin.empty() ||
      block.row_begin.back() != block.col.size() || block.col.size() != block.value.size()) {
    return absl::InvalidArgumentError(absl::StrCat("row block starting at row ", block.first_row,
                                                   " is malformed or out of order (next row is ",
                                                   rows_, ")"));
  }
  for (uint32_t c : block.col) {
    if (c >= cols_) {
      return absl::InvalidArgumentError(absl::StrCat("row block starting at row ", block.first_row,
                                                     " has column ", c, " >= ", cols_));
    }
  }
  if (open_.RowCount() == 0) {
    open_ = std::move(block);  // no copy for the first block of a chunk
  } else {
    AppendRows(block, open_);
  }
  rows_ = open_.first_row + open_.RowCount();
  return open_.Bytes() >= chunk_bytes_ ? Seal() : absl::OkStatus();
}

absl::Status RowStore::Finish() { return Seal(); }

absl::Status RowStore::Seal() {
  if (open_.RowCount() == 0) return absl::OkStatus();
  const uint64_t bytes = open_.Bytes();
  nnz_ += open_.col.size();
  if (memory_bytes_ + bytes <= budget_) {
    open_.col.shrink_to_fit();
    open_.value.shrink_to_fit();
    open_.row_begin.shrink_to_fit();
    chunks_.push_back({std::move(open_), -1});
    memory_bytes_ += bytes;
    open_ = EmptyChunk(rows_);
    return absl::OkStatus();
  }
  if (spill_ == nullptr) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "form-factor rows exceed the memory budget of ", budget_, " bytes and cannot spill"));
  }
  if (absl::Status s = spill_->Write(open_); !s.ok()) return s;
  chunks_.push_back({RowBlock{}, static_cast<int64_t>(spilled_chunks_++)});
  spilled_bytes_ += bytes;
  open_ = EmptyChunk(rows_);
  return absl::OkStatus();
}

absl::Status RowStore::ForEach(const RowsFn& fn) const {
  if (spilled_chunks_ > 0) return StreamWithReadAhead(fn);
  for (const Chunk& chunk : chunks_) fn(chunk.rows.View());
  return absl::OkStatus();
}

absl::Status RowStore::StreamWithReadAhead(const RowsFn& fn) const {
  struct Slot {
    RowBlock& block;  // a buffer of the store, reused pass after pass
    absl::Status status;
    bool full = false;
  };
  static_assert(kRowReadAhead == 2);
  std::array<Slot, kRowReadAhead> slots = {Slot{read_buffers_[0], {}, false},
                                           Slot{read_buffers_[1], {}, false}};
  std::mutex mutex;
  std::condition_variable changed;
  bool stop = false;
  uint64_t bytes = 0;
  double read_seconds = 0;

  std::thread reader([&] {
    for (size_t k = 0; k < spilled_chunks_; ++k) {
      Slot& slot = slots[k % kRowReadAhead];
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return stop || !slot.full; });
        if (stop) return;
      }
      const auto start = std::chrono::steady_clock::now();
      absl::Status status = spill_->Read(k, slot.block);
      read_seconds += SecondsSince(start);
      bytes += slot.block.Bytes();
      std::lock_guard lock(mutex);
      slot.status = std::move(status);
      slot.full = true;
      changed.notify_all();
      if (!slot.status.ok()) return;
    }
  });

  absl::Status result;
  double wait_seconds = 0;
  for (const Chunk& chunk : chunks_) {
    if (chunk.spill_index < 0) {
      fn(chunk.rows.View());
      continue;
    }
    Slot& slot = slots[static_cast<size_t>(chunk.spill_index) % kRowReadAhead];
    {
      const auto start = std::chrono::steady_clock::now();
      std::unique_lock lock(mutex);
      changed.wait(lock, [&] { return slot.full; });
      wait_seconds += SecondsSince(start);
      result = slot.status;
    }
    if (!result.ok()) break;
    fn(slot.block.View());
    std::lock_guard lock(mutex);
    slot.full = false;
    changed.notify_all();
  }
  {
    std::lock_guard lock(mutex);
    stop = true;
    changed.notify_all();
  }
  reader.join();
  read_stats_.passes += 1;
  read_stats_.bytes += bytes;
  read_stats_.read_seconds += read_seconds;
  read_stats_.wait_seconds += wait_seconds;
  return result;
}

absl::Status ForEachRows(const CsrMatrix* matrix, const RowStore* store, const RowsFn& fn) {
  if (matrix != nullptr) {
    fn(matrix->View());
    return absl::OkStatus();
  }
  return store->ForEach(fn);
}

}  // namespace radflux
