// CpuBudget: the cpu_seconds limit of a principal (principal.h) over one run of a job. A job
// holds `threads` of the server's threads while it runs, so its CPU time is taken as threads
// x running time (an upper bound of what it burns, and what it keeps from other jobs); once
// that reaches the limit, `on_spent` is called (once, from the budget's own thread).
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace radflux {

class CpuBudget {
 public:
  // `cpu_seconds` <= 0: no limit (no thread is started).
  CpuBudget(double cpu_seconds, int threads, std::function<void()> on_spent) {
    if (cpu_seconds <= 0) return;
    const auto wall = std::chrono::duration<double>(cpu_seconds / std::max(1, threads));
    watcher_ = std::thread([this, wall, on_spent = std::move(on_spent)] {
      std::unique_lock lock(mu_);
      if (!cv_.wait_for(lock, wall, [this] { return done_; })) on_spent();
    });
  }
  // The job's run ended: no call of `on_spent` after this returns.
  ~CpuBudget() {
    {
      std::lock_guard lock(mu_);
      done_ = true;
    }
    cv_.notify_all();
    if (watcher_.joinable()) watcher_.join();
  }
  CpuBudget(const CpuBudget&) = delete;
  CpuBudget& operator=(const CpuBudget&) = delete;

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  bool done_ = false;
  std::thread watcher_;
};

}  // namespace radflux
