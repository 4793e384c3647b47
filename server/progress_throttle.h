// ProgressThrottle: a job's progress events on their way to its hub, at most one per
// `interval`, always the newest. An event due sooner is held (replacing any held one) and
// published once the interval has passed (on the throttle's own thread) or at Flush, which
// the job calls before each phase change so that the order of events stays as published.
// Watchers then read at most 1/interval progress events per second, however fast the job
// reports: 50 watchers cost the server little. Phase changes, snapshots and the final event
// never go through it. Thread-safe.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "radflux/v1/job.pb.h"
#include "server/job_hub.h"

namespace radflux {

class ProgressThrottle {
 public:
  ProgressThrottle(JobHub& hub, std::chrono::milliseconds interval);
  ~ProgressThrottle();  // Flush(), then stops the thread
  ProgressThrottle(const ProgressThrottle&) = delete;
  ProgressThrottle& operator=(const ProgressThrottle&) = delete;

  // Publishes `event` now if the interval has passed since the last one, else holds it.
  void Publish(v1::JobEvent event);
  // Publishes the held event, if any, now.
  void Flush();

 private:
  using Clock = std::chrono::steady_clock;
  void Loop();
  // Publishes the held event (mu_ held: keeps the hub's order equal to the throttle's).
  void PublishHeldLocked(Clock::time_point now);

  JobHub& hub_;
  const Clock::duration interval_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::optional<v1::JobEvent> held_;
  Clock::time_point last_published_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace radflux
