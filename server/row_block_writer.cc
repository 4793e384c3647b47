#include "server/row_block_writer.h"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace radflux {

RowBlockWriter::RowBlockWriter(JobStore& store, std::string job_id, uint32_t block_size,
                               double interval_seconds)
    : store_(store),
      job_id_(std::move(job_id)),
      block_size_(std::max(1u, block_size)),
      interval_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(std::max(0.0, interval_seconds)))),
      next_checkpoint_(Clock::now() + interval_),
      thread_([this] { Loop(); }) {}

RowBlockWriter::~RowBlockWriter() { Finish(/*drain=*/true); }

void RowBlockWriter::Put(std::shared_ptr<const StoredRowBlock> block) {
  {
    std::lock_guard lock(mu_);
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
    if (!stopping_ && Clock::now() < next_checkpoint_) {
      cv_.wait_until(lock, next_checkpoint_);
      continue;
    }
    std::vector<std::shared_ptr<const StoredRowBlock>> blocks;
    blocks.swap(queue_);
    lock.unlock();
    Store(blocks);
    blocks.clear();  // release the rows before waiting again
    lock.lock();
    next_checkpoint_ = Clock::now() + interval_;
  }
}

void RowBlockWriter::Store(const std::vector<std::shared_ptr<const StoredRowBlock>>& blocks) {
  std::vector<const StoredRowBlock*> group;
  uint32_t first = UINT32_MAX;
  for (const auto& block : blocks) {
    group.push_back(block.get());
    first = std::min(first, block->block.first_row / block_size_);
  }
  if (absl::Status s = store_.PutRowBlocks(job_id_, first, group); !s.ok()) {
    spdlog::warn("job {}: {} row blocks not stored ({}); they are rebuilt if the job resumes",
                 job_id_, blocks.size(), std::string(s.message()));
  }
}

}  // namespace radflux
