// WorkQueue: a small fixed pool of threads for the blocking parts of RPCs (disk, SQLite,
// parsing), so gRPC's reactor threads never block.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace radflux {

class WorkQueue {
 public:
  explicit WorkQueue(int threads);
  // Runs the queued tasks still pending, then joins the threads.
  ~WorkQueue();
  WorkQueue(const WorkQueue&) = delete;
  WorkQueue& operator=(const WorkQueue&) = delete;

  // Queues `task` to run on one of the pool's threads.
  void Post(std::function<void()> task);

 private:
  void Loop();

  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> tasks_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace radflux
