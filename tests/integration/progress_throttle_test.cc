// ProgressThrottle: what reaches a job's hub. Intervals are an hour (never elapsing in a
// test) or zero, so nothing here depends on timing.
#include "server/jobs/progress_throttle.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <vector>

namespace radflux {
namespace {

using std::chrono::hours;
using std::chrono::milliseconds;

SnapshotData Snapshot(int iteration) {
  return {iteration, std::make_shared<const std::vector<Rgb>>(3, Rgb{})};
}

int NewestIteration(const JobHub& hub) {
  SnapshotData newest;
  return hub.NewestSnapshot(0, &newest) ? newest.iteration : -1;
}

v1::JobEvent Iteration(int iteration) {
  v1::JobEvent event;
  event.mutable_progress()->set_iteration(iteration);
  return event;
}

TEST(ProgressThrottleTest, SnapshotsWithinTheIntervalAreHeldAndFlushPublishesTheNewest) {
  JobHub hub("job-throttle");
  ProgressThrottle throttle(hub, hours(1), hours(1));
  for (int i = 1; i <= 5; ++i) throttle.PublishSnapshot(Snapshot(i));
  EXPECT_EQ(NewestIteration(hub), 1) << "the first goes out at once, the next are held";
  throttle.Flush();
  EXPECT_EQ(NewestIteration(hub), 5) << "Flush publishes the newest held, the job's last B";
}

TEST(ProgressThrottleTest, AfterRestartingTheIntervalTheFirstSnapshotIsHeldToo) {
  JobHub hub("job-throttle");
  ProgressThrottle throttle(hub, hours(1), hours(1));
  throttle.RestartSnapshotInterval();
  for (int i = 1; i <= 3; ++i) throttle.PublishSnapshot(Snapshot(i));
  EXPECT_EQ(NewestIteration(hub), -1) << "a solve shorter than the interval: nothing yet";
  throttle.Flush();
  EXPECT_EQ(NewestIteration(hub), 3) << "then its final B";
}

TEST(ProgressThrottleTest, ZeroSnapshotIntervalPublishesEverySnapshot) {
  JobHub hub("job-throttle");
  ProgressThrottle throttle(hub, hours(1), milliseconds(0));
  for (int i = 1; i <= 5; ++i) {
    throttle.PublishSnapshot(Snapshot(i));
    EXPECT_EQ(NewestIteration(hub), i);
  }
}

TEST(ProgressThrottleTest, EventsWithinTheIntervalCoalesceToTheNewest) {
  JobHub hub("job-throttle");
  ProgressThrottle throttle(hub, hours(1), hours(1));
  for (int i = 1; i <= 5; ++i) throttle.Publish(Iteration(i));
  EXPECT_EQ(hub.last_sequence(), 1u) << "the first goes out at once, the next are held";
  throttle.Flush();
  ASSERT_EQ(hub.last_sequence(), 2u) << "then only the newest";
  HubEvent second;
  ASSERT_TRUE(hub.NextEvent(1, &second));
  v1::JobEvent event;
  ASSERT_TRUE(event.ParseFromString(*second.wire));
  EXPECT_EQ(event.progress().iteration(), 5);
}

}  // namespace
}  // namespace radflux
