#include "server/jobs/progress_throttle.h"

#include <algorithm>

namespace radflux {

ProgressThrottle::ProgressThrottle(JobHub& hub, std::chrono::milliseconds interval,
                                   std::chrono::milliseconds snapshot_interval)
    : hub_(hub),
      event_{interval, std::nullopt, std::nullopt},
      snapshot_{snapshot_interval, std::nullopt, std::nullopt},
      thread_([this] { Loop(); }) {}

ProgressThrottle::~ProgressThrottle() {
  {
    std::lock_guard lock(mu_);
    stopping_ = true;
    PublishSnapshotLocked(Clock::now());
    PublishEventLocked(Clock::now());
  }
  cv_.notify_one();
  thread_.join();
}

void ProgressThrottle::Publish(v1::JobEvent event) {
  const Clock::time_point now = Clock::now();
  std::lock_guard lock(mu_);
  event_.held = std::move(event);
  if (event_.Due(now)) {
    PublishEventLocked(now);
  } else {
    cv_.notify_one();  // the thread publishes it when the interval has passed
  }
}

void ProgressThrottle::PublishSnapshot(SnapshotData snapshot) {
  const Clock::time_point now = Clock::now();
  std::lock_guard lock(mu_);
  snapshot_.held = std::move(snapshot);
  if (snapshot_.Due(now)) {
    PublishSnapshotLocked(now);
  } else {
    cv_.notify_one();
  }
}

void ProgressThrottle::RestartSnapshotInterval() {
  std::lock_guard lock(mu_);
  snapshot_.last_published = Clock::now();
}

void ProgressThrottle::Flush() {
  std::lock_guard lock(mu_);
  PublishSnapshotLocked(Clock::now());
  PublishEventLocked(Clock::now());
}

void ProgressThrottle::PublishEventLocked(Clock::time_point now) {
  if (!event_.held) return;
  hub_.Publish(*std::move(event_.held));
  event_.held.reset();
  event_.last_published = now;
}

void ProgressThrottle::PublishSnapshotLocked(Clock::time_point now) {
  if (!snapshot_.held) return;
  hub_.PublishSnapshot(*std::move(snapshot_.held));
  snapshot_.held.reset();
  snapshot_.last_published = now;
}

void ProgressThrottle::Loop() {
  std::unique_lock lock(mu_);
  while (!stopping_) {
    const Clock::time_point now = Clock::now();
    if (snapshot_.Due(now)) PublishSnapshotLocked(now);
    if (event_.Due(now)) PublishEventLocked(now);
    if (!event_.held && !snapshot_.held) {
      cv_.wait(lock);
      continue;
    }
    Clock::time_point wake = Clock::time_point::max();
    if (event_.held) wake = std::min(wake, event_.DueAt());
    if (snapshot_.held) wake = std::min(wake, snapshot_.DueAt());
    cv_.wait_until(lock, wake);
  }
}

}  // namespace radflux
