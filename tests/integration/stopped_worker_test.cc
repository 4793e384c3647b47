// Stopped and slow workers (issue 22): a worker stopped with SIGSTOP mid-block (its process
// frozen, its connection open) held its blocks for the whole lease, 300 s by default. Now
// the server hears a heartbeat from each worker every second: one silent for 5 s has its
// blocks leased to others, while a slow worker that still beats keeps its own; and once no
// block is pending, the server's threads build blocks held for 2 s as backups. The job
// ends bit-identical to RunJob either way. Leases here are an hour long, so only these
// mechanisms can finish the jobs; watches give up after a minute (a guard, not a timing).
#include <gtest/gtest.h>
#include <signal.h>

#include "tests/integration/worker_fixture.h"

namespace radflux {
namespace {

using testing::Child;
using testing::ExpectBitIdentical;
using testing::Options;
using testing::WorkerTest;

// Kills a child (stopped, or sleeping in a long block) when the test ends: a SIGTERM
// would wait for it.
struct KillAtEnd {
  Child& child;
  ~KillAtEnd() { child.Stop(SIGKILL); }
};

class StoppedWorkerTest : public WorkerTest {
 public:
  // Watches the job until it ends, for at most a minute; returns its last state.
  v1::JobState WatchWithin(const std::string& job_id) {
    v1::WatchJobRequest request;
    request.set_job_id(job_id);
    auto context = Context();
    context->set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    auto reader = stub_->WatchJob(context.get(), request);
    v1::JobEvent event;
    while (reader->Read(&event)) {
    }
    reader->Finish();
    return event.state();
  }
  // The worker's id as the server registered it.
  static std::string WorkerId(Child& worker) {
    return worker.WaitForLog("registered with \\S+ as worker (\\d+)")[1];
  }
};

// Once every other block is built, the server's own thread builds the stopped worker's
// block (a backup task), or, if it is busy past 5 s, the block is leased again for the
// worker's silence.
TEST_F(StoppedWorkerTest, StoppedWorkerBlockIsBuiltAsABackupAndTheResultIsIdentical) {
  StartServer({"--lease-seconds", "3600"});
  Child& fast = StartWorker({});
  // Holds each block 30 s after building it: the stop lands while it holds one.
  Child& stopped = StartWorker({"--testing-block-delay-ms", "30000"});
  fast.WaitForLog("registered with");
  const std::string stopped_id = WorkerId(stopped);
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  const std::string block = stopped.WaitForLog("building row block (\\d+) of job")[1];
  ASSERT_EQ(kill(stopped.pid(), SIGSTOP), 0);
  const KillAtEnd kill_stopped{stopped};
  ASSERT_EQ(WatchWithin(job_id), v1::JOB_STATE_SUCCEEDED);
  ExpectBitIdentical(Result(job_id), testing::InProcess(options), "the result differs");
  EXPECT_TRUE(std::regex_search(
      server_->Log(),
      std::regex("row block " + block + " (built here as a backup: worker " + stopped_id +
                 " |\\(rows \\d+\\.\\.\\d+\\) leased again: worker " + stopped_id +
                 " \\(\\S+\\) stopped answering)")))
      << server_->Log();
}

// The server's thread is busy for 15 s with a block of its own, so no backup can help: the
// stopped worker's block goes to another worker after 5 s of silence, while a slow worker
// that keeps sending heartbeats keeps its lease.
TEST_F(StoppedWorkerTest, SilentWorkerLosesItsBlockWhileASlowOneThatBeatsKeepsIt) {
  StartServer({"--lease-seconds", "3600", "--testing-block-delay-ms", "15000"});
  Child& stopped = StartWorker({"--testing-block-delay-ms", "30000"});
  const std::string stopped_id = WorkerId(stopped);
  Child& slow = StartWorker({"--testing-block-delay-ms", "8000"});
  const std::string slow_id = WorkerId(slow);
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  const std::string block = stopped.WaitForLog("building row block (\\d+) of job")[1];
  ASSERT_EQ(kill(stopped.pid(), SIGSTOP), 0);
  const KillAtEnd kill_stopped{stopped}, kill_slow{slow};
  Child& fast = StartWorker({});
  ASSERT_EQ(WatchWithin(job_id), v1::JOB_STATE_SUCCEEDED);
  ExpectBitIdentical(Result(job_id), testing::InProcess(options), "the result differs");
  const std::string log = server_->Log();
  EXPECT_TRUE(std::regex_search(
      log, std::regex("row block " + block + " \\(rows \\d+\\.\\.\\d+\\) leased again: worker " +
                      stopped_id + " \\(\\S+\\) stopped answering")))
      << log;
  EXPECT_FALSE(
      std::regex_search(log, std::regex("worker " + slow_id + " \\(\\S+\\) stopped answering")))
      << "the slow worker kept beating:\n"
      << log;
  EXPECT_GT(testing::CountOf(slow.Log(), "sent row block"), 0) << slow.Log();
  EXPECT_GT(testing::CountOf(fast.Log(), "sent row block " + block + " "), 0) << fast.Log();
}

}  // namespace
}  // namespace radflux
