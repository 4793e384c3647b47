// RowBlockWriter: stores a job's form-factor row blocks on a thread of its own, so the
// threads that build rows never wait for the disk (each block is written, fsynced and
// renamed: ~10 ms here, longer than building it). A block still queued when the process
// dies is rebuilt on resume (rows are deterministic per patch): only time is lost, never
// correctness. Failures are logged, not fatal, for the same reason. Thread-safe.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "server/job_store.h"

namespace radflux {

class RowBlockWriter {
 public:
  RowBlockWriter(JobStore& store, std::string job_id);
  ~RowBlockWriter();  // Finish(/*drain=*/true)
  RowBlockWriter(const RowBlockWriter&) = delete;
  RowBlockWriter& operator=(const RowBlockWriter&) = delete;

  // Queues block `index` for storing.
  void Put(uint32_t index, StoredRowBlock block);
  // Stops the thread once the queue is stored (drain) or at once, dropping what is queued
  // (the job finished: its row blocks are about to be deleted). Idempotent.
  void Finish(bool drain);

 private:
  void Loop();

  JobStore& store_;
  const std::string job_id_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::pair<uint32_t, StoredRowBlock>> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace radflux
