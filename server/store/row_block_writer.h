// RowBlockWriter: checkpoints a job's form-factor row blocks on a thread of its own, so the
// threads that build rows never wait for the disk. Blocks are gathered and stored together,
// one file (one write + fsync + rename) per checkpoint, at most one checkpoint per
// `interval_seconds` (0: as soon as the previous one is on disk), and sooner once the
// queue holds `max_group_bytes` of rows: a checkpoint's file, and the encoding buffers it
// needs, stay bounded whatever the job's size (the rows of a spilled job must not all wait
// in memory for one big checkpoint). Put waits while the queue holds twice that, so a
// writer starved of CPU by the builders slows them instead of letting rows pile up.
// A block not yet stored
// when the process dies is rebuilt on resume (rows are deterministic per patch): only time
// is lost, never correctness. A checkpoint that cannot be written (a full disk) is handed
// to `on_error`, once, and the writer stores nothing more (the job is to fail: its files go).
// Thread-safe.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "server/store/job_store.h"

namespace radflux {

class RowBlockWriter {
 public:
  // `block_size` rows per block: block k holds the rows from k * block_size.
  using ErrorSink = std::function<void(const absl::Status&)>;
  RowBlockWriter(JobStore& store, std::string job_id, uint32_t block_size, double interval_seconds,
                 size_t max_group_bytes = kDefaultMaxGroupBytes, ErrorSink on_error = {});
  static constexpr size_t kDefaultMaxGroupBytes = size_t{16} << 20;
  ~RowBlockWriter();  // Finish(/*drain=*/true)
  RowBlockWriter(const RowBlockWriter&) = delete;
  RowBlockWriter& operator=(const RowBlockWriter&) = delete;

  // Queues a block for the next checkpoint (shared: the writer never copies rows).
  void Put(std::shared_ptr<const StoredRowBlock> block);
  // Stops the thread once the queue is stored (drain: a last checkpoint now) or at once,
  // dropping what is queued (the job finished: its row blocks are about to be deleted).
  // Idempotent.
  void Finish(bool drain);

 private:
  using Clock = std::chrono::steady_clock;
  void Loop();
  void Store(const std::vector<std::shared_ptr<const StoredRowBlock>>& blocks);

  JobStore& store_;
  const std::string job_id_;
  const uint32_t block_size_;
  const Clock::duration interval_;
  std::mutex mu_;
  std::condition_variable cv_;       // wakes the writer
  std::condition_variable drained_;  // wakes a Put waiting for room
  const size_t max_group_bytes_;
  const ErrorSink on_error_;
  bool failed_ = false;  // a checkpoint failed: later ones are dropped (writer thread only)
  std::vector<std::shared_ptr<const StoredRowBlock>> queue_;
  size_t queued_bytes_ = 0;
  Clock::time_point next_checkpoint_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace radflux
