// The rounds of watcher wakes: WakeSchedule's policy on given times, and JobHub running
// them (intervals of an hour, never elapsing in a test; waits bounded only to fail, not hang).
#include "server/job_hub.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>

namespace radflux {
namespace {

using Clock = WakeSchedule::Clock;
using std::chrono::milliseconds;

TEST(WakeScheduleTest, AtMostOneRoundPerIntervalAndTheJobsEndAtOnce) {
  WakeSchedule schedule(milliseconds(100));
  const Clock::time_point t0 = Clock::now();
  EXPECT_EQ(schedule.Request(t0, false), t0) << "the first change: at once";
  EXPECT_EQ(schedule.Request(t0 + milliseconds(1), false), std::nullopt) << "shares the pending";
  EXPECT_TRUE(schedule.Start(t0, t0 + milliseconds(2)));
  EXPECT_EQ(schedule.Request(t0 + milliseconds(10), false), t0 + milliseconds(102))
      << "the next round waits for the interval from the last start";
  EXPECT_EQ(schedule.Request(t0 + milliseconds(50), false), std::nullopt);
  EXPECT_EQ(schedule.Request(t0 + milliseconds(60), true), t0 + milliseconds(60))
      << "the job's end does not wait";
  EXPECT_FALSE(schedule.Start(t0 + milliseconds(102), t0 + milliseconds(102)))
      << "the round it replaced does not run";
  EXPECT_FALSE(schedule.Start(t0 + milliseconds(102), t0 + milliseconds(103)));
}

TEST(WakeScheduleTest, ARoundReplacedBeforeItRanDoesNotRunAndTheSoonerOneDoes) {
  WakeSchedule schedule(milliseconds(100));
  const Clock::time_point t0 = Clock::now();
  ASSERT_TRUE(schedule.Request(t0, false));
  ASSERT_TRUE(schedule.Start(t0, t0));
  ASSERT_EQ(schedule.Request(t0 + milliseconds(5), false), t0 + milliseconds(100));
  ASSERT_EQ(schedule.Request(t0 + milliseconds(6), true), t0 + milliseconds(6));
  EXPECT_TRUE(schedule.Start(t0 + milliseconds(6), t0 + milliseconds(7)));
  EXPECT_FALSE(schedule.Start(t0 + milliseconds(100), t0 + milliseconds(100)));
  EXPECT_EQ(schedule.Request(t0 + milliseconds(8), false), t0 + milliseconds(107))
      << "the interval runs from the urgent round's start";
}

TEST(WakeScheduleTest, ChangesAfterAQuietIntervalWakeAtOnce) {
  WakeSchedule schedule(milliseconds(100));
  const Clock::time_point t0 = Clock::now();
  ASSERT_TRUE(schedule.Request(t0, false));
  ASSERT_TRUE(schedule.Start(t0, t0));
  EXPECT_EQ(schedule.Request(t0 + milliseconds(500), false), t0 + milliseconds(500));
}

TEST(WakeScheduleTest, ZeroIntervalWakesForEveryChangeAfterTheLastRound) {
  WakeSchedule schedule(milliseconds(0));
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 3; ++i) {
    const Clock::time_point t = t0 + milliseconds(i);
    ASSERT_EQ(schedule.Request(t, false), t);
    ASSERT_TRUE(schedule.Start(t, t));
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

TEST(JobHubTest, TheFirstChangeAndTheJobsEndWakeAtOnceWhateverTheInterval) {
  auto hub = std::make_shared<JobHub>("job-hub", 0, std::chrono::hours(1));
  RoundCounter counter;
  const int id = hub->Subscribe(counter.Wake());
  hub->Publish(Event(v1::JOB_STATE_RUNNING));
  EXPECT_EQ(counter.WaitFor(1), 1) << "the first change wakes at once";
  for (int i = 0; i < 5; ++i) hub->Publish(Event(v1::JOB_STATE_RUNNING));
  hub->PublishSnapshot({1, std::make_shared<const std::vector<Rgb>>(3, Rgb{})});
  hub->Publish(Event(v1::JOB_STATE_SUCCEEDED));
  EXPECT_EQ(counter.WaitFor(2), 2) << "the final event does not wait for the interval";
  EXPECT_EQ(EventsVisible(*hub), 7u) << "the round finds every event published before it";
  hub->Close();
  EXPECT_EQ(counter.WaitFor(3), 3) << "nor does Close";
  hub->Unsubscribe(id);
}

}  // namespace
}  // namespace radflux
