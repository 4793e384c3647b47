// WakeSchedule: when a job hub's next round of watcher wakes is due. A change is due one
// interval after it is made, and changes made while a round is pending share it, so rounds
// start at most once per interval and each carries every change of its interval; an urgent
// change (the job's end) is due at once. Pure logic on given times (the hub calls it under
// its lock), so the policy is tested without clocks.
#pragma once

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
    const Clock::time_point due = urgent ? now : now + interval_;
    if (pending_ && due_ <= due) return std::nullopt;
    pending_ = true;
    due_ = due;
    return due;
  }

  // Whether the round scheduled for `due` is the pending one, which then starts; false if a
  // sooner one replaced it (or it already ran).
  bool Start(Clock::time_point due) {
    if (!pending_ || due != due_) return false;
    pending_ = false;
    return true;
  }

 private:
  const Clock::duration interval_;
  bool pending_ = false;
  Clock::time_point due_;  // of the pending round
};

}  // namespace radflux
