// ParallelFor's thread counts (solver/core/parallel.h): ThreadCount bounds ThreadIndex, and a
// ScopedThreadCount bounds "all cores" on its own thread only, until it ends.
#include "solver/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace radflux {
namespace {

// The largest ThreadIndex() + 1 seen by ParallelFor(count, 1, threads).
int ThreadsSeen(int threads) {
  std::atomic<int> seen{0};
  ParallelFor(64, 1, threads, [&](int64_t, int64_t) {
    const int t = ThreadIndex() + 1;
    int s = seen.load();
    while (t > s && !seen.compare_exchange_weak(s, t)) {
    }
  });
  return seen.load();
}

TEST(ParallelFor, ThreadIndexStaysBelowThreadCount) {
  for (const int threads : {0, 1, 3, 2 * DefaultThreadCount() + 1}) {
    EXPECT_LE(ThreadsSeen(threads), ThreadCount(threads)) << threads;
  }
  EXPECT_EQ(ThreadCount(0), DefaultThreadCount());
  EXPECT_EQ(ThreadCount(5), 5);
}

TEST(ParallelFor, ScopedThreadCountBoundsAllCoresOnItsThreadOnly) {
  const int all = DefaultThreadCount();
  {
    const ScopedThreadCount one(1);
    EXPECT_EQ(DefaultThreadCount(), 1);
    EXPECT_EQ(ThreadsSeen(0), 1);
    int other = 0;  // a job on another thread keeps all cores
    std::thread([&] { other = DefaultThreadCount(); }).join();
    EXPECT_EQ(other, all);
    {
      const ScopedThreadCount unchanged(0);  // 0: all cores as they are
      EXPECT_EQ(DefaultThreadCount(), 1);
    }
    EXPECT_EQ(DefaultThreadCount(), 1);
  }
  EXPECT_EQ(DefaultThreadCount(), all);
}

}  // namespace
}  // namespace radflux
