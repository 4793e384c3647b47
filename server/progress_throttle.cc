#include "server/progress_throttle.h"

namespace radflux {

ProgressThrottle::ProgressThrottle(JobHub& hub, std::chrono::milliseconds interval)
    : hub_(hub), interval_(interval), thread_([this] { Loop(); }) {}

ProgressThrottle::~ProgressThrottle() {
  {
    std::lock_guard lock(mu_);
    stopping_ = true;
    PublishHeldLocked(Clock::now());
  }
  cv_.notify_one();
  thread_.join();
}

void ProgressThrottle::Publish(v1::JobEvent event) {
  const Clock::time_point now = Clock::now();
  std::lock_guard lock(mu_);
  held_ = std::move(event);
  if (now - last_published_ >= interval_) {
    PublishHeldLocked(now);
  } else {
    cv_.notify_one();  // the thread publishes it when the interval has passed
  }
}

void ProgressThrottle::Flush() {
  std::lock_guard lock(mu_);
  PublishHeldLocked(Clock::now());
}

void ProgressThrottle::PublishHeldLocked(Clock::time_point now) {
  if (!held_) return;
  hub_.Publish(*std::move(held_));
  held_.reset();
  last_published_ = now;
}

void ProgressThrottle::Loop() {
  std::unique_lock lock(mu_);
  while (!stopping_) {
    if (!held_) {
      cv_.wait(lock);
    } else if (Clock::now() - last_published_ < interval_) {
      cv_.wait_until(lock, last_published_ + interval_);
    } else {
      PublishHeldLocked(Clock::now());
    }
  }
}

}  // namespace radflux
