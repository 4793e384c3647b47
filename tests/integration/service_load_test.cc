// The service under load: many jobs and watchers (slow, stalled) never hold a job back,
// and finished jobs leave memory but stay watchable (a server per test on loopback).
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <thread>

#include "radflux/v1/radiosity.grpc.pb.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"

namespace radflux {
namespace {

using testing::SmallOptions;

class ServiceLoadTest : public testing::ServiceFixture {};

// Resident memory of a process in KiB (VmRSS of /proc/PID/status), 0 if unreadable.
int64_t ResidentKiB(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6));
  }
  return 0;
}

// Ten jobs at once and fifty watchers asking for a float32 snapshot every iteration:
// 20 read as fast as they can, 15 sleep 20 ms between reads, 10 read one event and then
// stop reading until every job has finished, 5 disconnect after three events. Asserts:
// every job ends SUCCEEDED while the stalled watchers are not reading (so no watcher holds
// a job back); every watcher that stays gets a gap-free event history ending SUCCEEDED;
// the server's resident memory stays below 1 GiB.
TEST_F(ServiceLoadTest, TenJobsFiftyWatchersSlowAndStalledNeverHoldAJobBack) {
  StartServer({"--jobs", "10"});
  const int64_t rss_before = ResidentKiB(server_->pid());
  const std::string sha = UploadCornell();
  std::vector<std::string> jobs;
  for (int i = 0; i < 10; ++i) {
    v1::SolveOptions options = SmallOptions(500, i % 2 ? "cg" : "jacobi");
    options.set_seed(100 + i);
    v1::Job job;
    ASSERT_TRUE(Submit(options, &job, sha).ok());
    jobs.push_back(job.job_id());
  }
  std::mutex mu;
  std::condition_variable all_done_cv;
  bool all_done = false;
  std::vector<std::string> failures;
  const auto watcher = [&](int w) {
    // Its own connection, so a watcher that does not read fills only its own windows.
    grpc::ChannelArguments args;
    args.SetInt("radflux.test.watcher", w);
    auto stub = v1::Radiosity::NewStub(
        grpc::CreateCustomChannel(server_->address(), grpc::InsecureChannelCredentials(), args));
    v1::WatchJobRequest request;
    request.set_job_id(jobs[static_cast<size_t>(w % 10)]);
    request.set_snapshot_every(1);
    request.set_snapshot_format(v1::SNAPSHOT_FORMAT_FLOAT32);
    // Fifty connections opened at once to a server busy with ten jobs: one may fail its
    // first attempt (CI saw "failed to connect to all addresses" once), so each watcher waits
    // for its channel to connect, as a patient client does, and gives up after two minutes.
    grpc::ClientContext context;
    context.set_wait_for_ready(true);
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::minutes(2));
    auto reader = stub->WatchJob(&context, request);
    v1::JobEvent event;
    uint64_t last = 0;
    int read = 0;
    v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
    while (reader->Read(&event)) {
      ++read;
      if (!event.has_snapshot()) {
        if (event.sequence() != last + 1) {
          std::lock_guard lock(mu);
          failures.push_back("watcher " + std::to_string(w) + ": sequence gap");
        }
        last = event.sequence();
        state = event.state();
      }
      if (w >= 45 && read == 3) {  // disconnects early
        context.TryCancel();
        break;
      }
      if (w >= 35 && w < 45 && read == 1) {  // stalls until every job has finished
        std::unique_lock lock(mu);
        all_done_cv.wait(lock, [&] { return all_done; });
      }
      if (w >= 20 && w < 35) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    const grpc::Status finished = reader->Finish();
    if (w < 45 && state != v1::JOB_STATE_SUCCEEDED) {
      std::lock_guard lock(mu);
      failures.push_back("watcher " + std::to_string(w) + ": ended " + v1::JobState_Name(state) +
                         " after " + std::to_string(read) + " messages, stream status " +
                         std::to_string(finished.error_code()) + " " + finished.error_message());
    }
  };
  std::vector<std::thread> watchers;
  for (int w = 0; w < 50; ++w) watchers.emplace_back(watcher, w);

  // Every job finishes while ten watchers are not reading at all.
  for (;;) {
    v1::ListJobsResponse list;
    ASSERT_TRUE(stub_->ListJobs(Context().get(), {}, &list).ok());
    int succeeded = 0;
    for (const v1::Job& job : list.jobs()) {
      ASSERT_NE(job.state(), v1::JOB_STATE_FAILED) << job.message();
      succeeded += job.state() == v1::JOB_STATE_SUCCEEDED;
    }
    if (succeeded == 10) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  {
    std::lock_guard lock(mu);
    all_done = true;
  }
  all_done_cv.notify_all();
  for (std::thread& t : watchers) t.join();
  std::string all_failures;
  for (const std::string& failure : failures) all_failures += failure + "\n";
  EXPECT_TRUE(failures.empty()) << all_failures;
  const int64_t rss_after = ResidentKiB(server_->pid());
  EXPECT_GT(rss_before, 0);
  EXPECT_LT(rss_after, 1 << 20) << "server RSS " << rss_after << " KiB (was " << rss_before << ")";
  std::cerr << "server RSS before " << rss_before << " KiB, after " << rss_after << " KiB\n";
}

// The server keeps the event hubs (with their last snapshot) of only the 64 newest finished
// jobs in memory. A job finished 70 jobs ago is still watchable: its history is rebuilt from
// the store and ends with its terminal state.
TEST_F(ServiceLoadTest, OldFinishedJobsLeaveMemoryButStayWatchable) {
  StartServer({"--jobs", "2"});
  v1::SceneRef ref;
  const std::string obj =
      "usemtl lamp\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
      "usemtl wall\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 5 8 7 6\n";
  const std::string mtl = "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\nnewmtl wall\nKd 0.8 0.8 0.8\n";
  ASSERT_TRUE(Upload(obj, mtl, &ref).ok());
  std::vector<std::string> jobs;
  for (int i = 0; i < 70; ++i) {
    v1::Job job;
    ASSERT_TRUE(Submit(SmallOptions(4, "cg"), &job, ref.sha256()).ok());
    jobs.push_back(job.job_id());
  }
  // Waits for every job without watching it: a watch of a job whose hub was pruned rebuilds
  // it, which prunes the oldest kept one, so watching the jobs in turn after they all ended
  // would rebuild them one after the other up to the newest (the test used to, and passed
  // only while it watched each job before it was pruned).
  for (const std::string& id : jobs) {
    v1::GetJobRequest request;
    request.set_job_id(id);
    v1::Job job;
    for (;;) {
      ASSERT_TRUE(stub_->GetJob(Context().get(), request, &job).ok());
      if (IsTerminal(job.state())) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_EQ(job.state(), v1::JOB_STATE_SUCCEEDED) << id;
  }
  const std::vector<v1::JobEvent> first = Watch(jobs.front());
  ASSERT_EQ(first.size(), 1u) << "a pruned hub is rebuilt from the store as one event";
  EXPECT_EQ(first.back().state(), v1::JOB_STATE_SUCCEEDED);
  const std::vector<v1::JobEvent> last = Watch(jobs.back());
  EXPECT_GT(last.size(), 1u) << "the newest finished jobs keep their whole history";
  EXPECT_EQ(last.back().state(), v1::JOB_STATE_SUCCEEDED);
}

}  // namespace
}  // namespace radflux
