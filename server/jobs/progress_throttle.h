// ProgressThrottle: a job's progress events and snapshots on their way to its hub, each at
// most one per its interval, always the newest. One due sooner is held (replacing any held
// one of its kind) and published once its interval has passed (on the throttle's own
// thread) or at Flush, which the job calls before each phase change and after its last
// iteration, so that the order of events stays as published and the job's final B always
// reaches the hub before its final event. Watchers then read at most 1/interval progress
// events and 1/snapshot_interval snapshots per second, however fast the job iterates: 50
// watchers cost the server little. Phase changes and the final event never go through it.
// Thread-safe.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "radflux/v1/job.pb.h"
#include "server/jobs/job_hub.h"

namespace radflux {

class ProgressThrottle {
 public:
  ProgressThrottle(JobHub& hub, std::chrono::milliseconds interval,
                   std::chrono::milliseconds snapshot_interval);
  ~ProgressThrottle();  // Flush(), then stops the thread
  ProgressThrottle(const ProgressThrottle&) = delete;
  ProgressThrottle& operator=(const ProgressThrottle&) = delete;

  // Publishes `event` now if `interval` has passed since the last one, else holds it.
  void Publish(v1::JobEvent event);
  // Publishes `snapshot` now if `snapshot_interval` has passed since the last one, else
  // holds it.
  void PublishSnapshot(SnapshotData snapshot);
  // Starts the snapshot interval now: the next snapshot is due one interval from now (the
  // job calls it when its solve starts, so that a solve shorter than the interval sends
  // its final B only, and a longer one a snapshot per interval).
  void RestartSnapshotInterval();
  // Publishes the held snapshot and event, if any, now.
  void Flush();

 private:
  using Clock = std::chrono::steady_clock;
  // The newest item of one kind not yet published, and when the last one was.
  template <typename T>
  struct Slot {
    Clock::duration interval;
    std::optional<T> held;
    std::optional<Clock::time_point> last_published;  // none yet: the first is due at once
    bool Due(Clock::time_point now) const {
      return held && (!last_published || now - *last_published >= interval);
    }
    // When the held item is due (called with one held that is not due yet).
    Clock::time_point DueAt() const { return *last_published + interval; }
  };
  void Loop();
  // Publish the held item (mu_ held: keeps the hub's order equal to the throttle's).
  void PublishEventLocked(Clock::time_point now);
  void PublishSnapshotLocked(Clock::time_point now);

  JobHub& hub_;
  std::mutex mu_;
  std::condition_variable cv_;
  Slot<v1::JobEvent> event_;
  Slot<SnapshotData> snapshot_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace radflux
