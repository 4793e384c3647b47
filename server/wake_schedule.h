// WakeSchedule: when a job hub's next round of watcher wakes is due. At most one round starts
// per interval; an urgent request (the job's end) is due at once; a request while a round is
// pending shares it unless it must start sooner. Pure logic on given times (the hub calls it
// under its lock), so the policy is tested without clocks.
#pragma once

#include <algorithm>
#include <chrono>
#include <optional>

namespace radflux {

class WakeSchedule {
 public:
  using Clock = std::chrono::steady_clock;
  explicit WakeSchedule(Clock::duration interval) : interval_(interval) {}

  // A change at `now`: the due time of a round to schedule, or none if the pending one
  // starts no later.
  std::optional<Clock::time_point> Request(Clock::time_point now, bool urgent) {
    Clock::time_point due = now;
    if (!urgent && started_any_) due = std::max(now, last_start_ + interval_);
    if (pending_ && due_ <= due) return std::nullopt;
    pending_ = true;
    due_ = due;
    return due;
  }

  // The round scheduled for `due` is to start at `now`: false if a sooner one replaced it
  // (or already ran), true if it starts (and the interval runs from `now`).
  bool Start(Clock::time_point due, Clock::time_point now) {
    if (!pending_ || due != due_) return false;
    pending_ = false;
    started_any_ = true;
    last_start_ = now;
    return true;
  }

 private:
  const Clock::duration interval_;
  bool pending_ = false;
  Clock::time_point due_;  // of the pending round
  bool started_any_ = false;
  Clock::time_point last_start_;  // of the last round
};

}  // namespace radflux
