#include "server/row_block_writer.h"

#include <spdlog/spdlog.h>

namespace radflux {

RowBlockWriter::RowBlockWriter(JobStore& store, std::string job_id)
    : store_(store), job_id_(std::move(job_id)), thread_([this] { Loop(); }) {}

RowBlockWriter::~RowBlockWriter() { Finish(/*drain=*/true); }

void RowBlockWriter::Put(uint32_t index, StoredRowBlock block) {
  {
    std::lock_guard lock(mu_);
    queue_.emplace_back(index, std::move(block));
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
  for (;;) {
    std::pair<uint32_t, StoredRowBlock> next;
    {
      std::unique_lock lock(mu_);
      cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, nothing (left) to store
      next = std::move(queue_.front());
      queue_.pop_front();
    }
    if (absl::Status s = store_.PutRowBlock(job_id_, next.first, next.second); !s.ok()) {
      spdlog::warn("job {}: row block {} not stored ({}); it is rebuilt if the job resumes",
                   job_id_, next.first, std::string(s.message()));
    }
  }
}

}  // namespace radflux
