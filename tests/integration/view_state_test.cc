// ViewState (client/view/view_state.h): latest wins. Snapshots replace each other, a reader
// gets the newest state and each residual point once, and a writer never waits for readers.
#include "client/view/view_state.h"

#include <gtest/gtest.h>

#include <thread>

namespace radflux::cli {
namespace {

ViewSnapshot Snapshot(int iteration) { return {iteration, 0, std::string(6, char(iteration)), 2.0}; }

TEST(ViewState, SnapshotsReplaceEachOtherAndAreNumbered) {
  ViewState state;
  EXPECT_EQ(state.Snapshot(), nullptr);
  for (int i = 1; i <= 1000; ++i) state.PublishSnapshot(Snapshot(i));
  std::shared_ptr<const ViewSnapshot> newest = state.Snapshot();
  ASSERT_NE(newest, nullptr);
  EXPECT_EQ(newest->iteration, 1000);
  EXPECT_EQ(newest->serial, 1000u);
  EXPECT_EQ(newest->half_rgb, std::string(6, char(1000)));
  size_t cursor = 0;
  const nlohmann::json m = nlohmann::json::parse(state.Message(&cursor));
  EXPECT_EQ(m["snapshot_serial"], 1000);
  EXPECT_EQ(m["snapshot_iteration"], 1000);
}

TEST(ViewState, EachResidualPointReachesAReaderOnce) {
  ViewState state;
  size_t cursor = 0;
  state.Publish({{"phase", "solving"}}, 1, 0.5);
  state.Publish({{"phase", "solving"}}, 1, 0.5);  // the same iteration again: one point
  state.Publish({{"phase", "solving"}}, 2, 0.1);
  nlohmann::json m = nlohmann::json::parse(state.Message(&cursor));
  EXPECT_EQ(m["phase"], "solving");
  EXPECT_EQ(m["residuals"], nlohmann::json::parse("[[1, 0.5], [2, 0.1]]"));
  state.Publish({{"phase", "solving"}}, 3, 0.01);
  state.Publish({{"phase", "rows"}}, 0, 0);  // no residual: no point
  m = nlohmann::json::parse(state.Message(&cursor));
  EXPECT_EQ(m["residuals"], nlohmann::json::parse("[[3, 0.01]]"));
  EXPECT_EQ(m["phase"], "rows") << "the newest progress only";
  size_t fresh = 0;
  EXPECT_EQ(nlohmann::json::parse(state.Message(&fresh))["residuals"].size(), 3u)
      << "a tab opened later gets every point";
}

TEST(ViewState, ReadersWakeOnChangeAndSkipVersionsInBetween) {
  ViewState state;
  const uint64_t start = state.WaitNewer(0, std::chrono::milliseconds(0));
  std::thread writer([&] {
    for (int i = 1; i <= 50; ++i) state.PublishSnapshot(Snapshot(i));
    state.End("{}", "glb");
  });
  writer.join();  // the writer finished without any reader: it never waits for one
  const uint64_t now = state.WaitNewer(start, std::chrono::hours(1));
  EXPECT_EQ(now, start + 51) << "one wake-up for 51 changes";
  EXPECT_EQ(state.WaitNewer(now, std::chrono::milliseconds(1)), now) << "nothing newer: timeout";
  size_t cursor = 0;
  const nlohmann::json m = nlohmann::json::parse(state.Message(&cursor));
  EXPECT_TRUE(m["ended"]);
  EXPECT_TRUE(m["has_glb"]);
  EXPECT_EQ(state.glb(), "glb");
}

TEST(ViewState, FailureEndsTheViewWithItsMessage) {
  ViewState state;
  state.Fail("job job-x not found");
  size_t cursor = 0;
  const nlohmann::json m = nlohmann::json::parse(state.Message(&cursor));
  EXPECT_TRUE(m["ended"]);
  EXPECT_EQ(m["error"], "job job-x not found");
  EXPECT_FALSE(m["has_report"]);
}

}  // namespace
}  // namespace radflux::cli
