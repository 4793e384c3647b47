#include "server/store/row_block_writer.h"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace radflux {

namespace {

size_t BlockBytes(const StoredRowBlock& b) {
  return b.block.col.size() * sizeof(uint32_t) + b.block.value.size() * sizeof(float) +
         b.block.row_begin.size() * sizeof(uint64_t);
}

}  // namespace

RowBlockWriter::RowBlockWriter(JobStore& store, std::string job_id, uint32_t block_size,
                               double interval_seconds, size_t max_group_bytes,
                               ErrorSink on_error)
    : store_(store),
      job_id_(std::move(job_id)),
      block_size_(std::max(1u, block_size)),
      interval_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(std::max(0.0, interval_seconds)))),
      max_group_bytes_(std::max<size_t>(1, max_group_bytes)),
      on_error_(std::move(on_error)),
      next_checkpoint_(Clock::now() + interval_),
      thread_([this] { Loop(); }) {}

RowBlockWriter::~RowBlockWriter() { Finish(/*drain=*/true); }

void RowBlockWriter::Put(std::shared_ptr<const StoredRowBlock> block) {
  {
    std::unique_lock lock(mu_);
    drained_.wait(lock, [&] { return stopping_ || queued_bytes_ < 2 * max_group_bytes_; });
    queued_bytes_ += BlockBytes(*block);
    queue_.push_back(std::move(block));
  }
  cv_.notify_one();
}

void RowBlockWriter::Finish(bool drain) {
  {
    std::lock_guard lock(mu_);
    stopping_ = true;
    if (!drain) queue_.clear();
  }
  cv_.notify_one();
  drained_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void RowBlockWriter::Loop() {
  std::unique_lock lock(mu_);
  for (;;) {
    if (queue_.empty()) {
      if (stopping_) return;
      cv_.wait(lock);
      continue;
    }
    if (!stopping_ && Clock::now() < next_checkpoint_ && queued_bytes_ < max_group_bytes_) {
      cv_.wait_until(lock, next_checkpoint_);
      continue;
    }
    std::vector<std::shared_ptr<const StoredRowBlock>> blocks;
    blocks.swap(queue_);
    queued_bytes_ = 0;
    drained_.notify_all();
    lock.unlock();
    Store(blocks);
    blocks.clear();  // release the rows before waiting again
    lock.lock();
    next_checkpoint_ = Clock::now() + interval_;
  }
}

void RowBlockWriter::Store(const std::vector<std::shared_ptr<const StoredRowBlock>>& blocks) {
  if (failed_) return;
  std::vector<const StoredRowBlock*> group;
  uint32_t first = UINT32_MAX;
  for (const auto& block : blocks) {
    group.push_back(block.get());
    first = std::min(first, block->block.first_row / block_size_);
  }
  if (absl::Status s = store_.PutRowBlocks(job_id_, first, group); !s.ok()) {
    spdlog::warn("job {}: {} row blocks not stored: {}", job_id_, blocks.size(),
                 std::string(s.message()));
    failed_ = true;
    if (on_error_) on_error_(s);
  }
}

}  // namespace radflux
