// The rounds of watcher wakes: WakeSchedule's policy on given times, and JobHub running
// them (intervals of an hour, never elapsing in a test; waits bounded only to fail, not hang).
#include "server/jobs/job_hub.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace radflux {
namespace {

using Clock = WakeSchedule::Clock;
using std::chrono::milliseconds;

TEST(WakeScheduleTest, AChangeIsDueOneIntervalLaterAndTheJobsEndAtOnce) {
  WakeSchedule schedule(milliseconds(100));
  const Clock::time_point t0 = Clock::now();
  EXPECT_EQ(schedule.Request(t0, false), t0 + milliseconds(100));
  EXPECT_EQ(schedule.Request(t0 + milliseconds(30), false), std::nullopt)
      << "a change while a round is pending shares it";
  EXPECT_EQ(schedule.Request(t0 + milliseconds(60), true), t0 + milliseconds(60))
      << "the job's end does not wait";
  EXPECT_FALSE(schedule.Start(t0 + milliseconds(100))) << "the round it replaced does not run";
  EXPECT_TRUE(schedule.Start(t0 + milliseconds(60)));
  EXPECT_FALSE(schedule.Start(t0 + milliseconds(60))) << "a round runs once";
}

TEST(WakeScheduleTest, RoundsStartAtMostOncePerInterval) {
  WakeSchedule schedule(milliseconds(100));
  const Clock::time_point t0 = Clock::now();
  std::optional<Clock::time_point> pending;
  std::vector<int> starts;                // ms
  for (int ms = 0; ms < 1000; ms += 7) {  // a change every 7 ms, rounds run when due
    const Clock::time_point now = t0 + milliseconds(ms);
    if (pending && *pending <= now) {
      ASSERT_TRUE(schedule.Start(*pending));
      starts.push_back(ms);
      pending.reset();
    }
    if (std::optional<Clock::time_point> due = schedule.Request(now, false)) pending = due;
  }
  EXPECT_EQ(starts, (std::vector<int>{105, 210, 315, 420, 525, 630, 735, 840, 945}))
      << "a round at the first step one interval after the first change it carries";
}

TEST(WakeScheduleTest, ZeroIntervalWakesAtOnce) {
  WakeSchedule schedule(milliseconds(0));
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 3; ++i) {
    const Clock::time_point t = t0 + milliseconds(i);
    ASSERT_EQ(schedule.Request(t, false), t);
    ASSERT_TRUE(schedule.Start(t));
  }
}

// Counts the rounds of wakes a hub runs, and waits for them.
class RoundCounter {
 public:
  std::function<void()> Wake() {
    return [this] {
      std::lock_guard lock(mu_);
      ++rounds_;
      cv_.notify_all();
    };
  }
  // Waits (at most a minute: a failure, not a hang) until `rounds` have run.
  int WaitFor(int rounds) {
    std::unique_lock lock(mu_);
    cv_.wait_for(lock, std::chrono::minutes(1), [&] { return rounds_ >= rounds; });
    return rounds_;
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  int rounds_ = 0;
};

v1::JobEvent Event(v1::JobState state) {
  v1::JobEvent event;
  event.set_state(state);
  return event;
}

uint64_t EventsVisible(const JobHub& hub) {
  uint64_t after = 0;
  HubEvent event;
  while (hub.NextEvent(after, &event)) after = event.sequence;
  return after;
}

TEST(JobHubTest, TheJobsEndWakesAtOnceWithEveryChangeOfTheInterval) {
  auto hub = std::make_shared<JobHub>("job-hub", 0, std::chrono::hours(1));
  RoundCounter counter;
  const int id = hub->Subscribe(counter.Wake());
  for (int i = 0; i < 6; ++i) hub->Publish(Event(v1::JOB_STATE_RUNNING));  // due in an hour
  hub->PublishSnapshot({1, std::make_shared<const std::vector<Rgb>>(3, Rgb{})});
  hub->Publish(Event(v1::JOB_STATE_SUCCEEDED));
  EXPECT_EQ(counter.WaitFor(1), 1) << "the final event does not wait for the interval";
  EXPECT_EQ(EventsVisible(*hub), 7u) << "its round finds every event published before it";
  hub->Close();
  EXPECT_EQ(counter.WaitFor(2), 2) << "nor does Close";
  hub->Unsubscribe(id);
}

TEST(JobHubTest, ZeroIntervalWakesForEveryChange) {
  auto hub = std::make_shared<JobHub>("job-hub", 0, std::chrono::milliseconds(0));
  RoundCounter counter;
  const int id = hub->Subscribe(counter.Wake());
  for (int i = 1; i <= 3; ++i) {
    hub->Publish(Event(v1::JOB_STATE_RUNNING));
    EXPECT_EQ(counter.WaitFor(i), i);
  }
  hub->Unsubscribe(id);
}

}  // namespace
}  // namespace radflux
