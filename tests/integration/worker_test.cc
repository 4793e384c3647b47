// Integration tests of worker nodes: radfluxd plus `radfluxd --worker` processes on
// loopback (and, where `ip netns` works, in separate network namespaces). Every test starts
// its own processes and stops them; results are compared bit for bit with RunJob.
#include <gtest/gtest.h>

#include "tests/integration/worker_fixture.h"

namespace radflux {
namespace {

using testing::Child;
using testing::CountOf;
using testing::Options;
using testing::ReadText;
using testing::WorkerTest;

TEST_F(WorkerTest, ServerPlusThreeWorkersEqualsInProcessRunJobBitForBit) {
  StartServer({});
  for (int i = 0; i < 3; ++i) StartWorker({});
  for (auto& w : workers_) w->WaitForLog("registered with");
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  ExpectSucceedsBitIdentical(job_id, options);
  for (auto& w : workers_) {
    EXPECT_GT(CountOf(w->Log(), "sent row block"), 0) << "every worker built blocks:\n" << w->Log();
  }
  EXPECT_EQ(CountOf(server_->Log(), "dropped"), 0) << server_->Log();
}

TEST_F(WorkerTest, KillNineWorkerMidBlockTheBlockIsLeasedAgainAndTheResultIsIdentical) {
  StartServer({});
  // The worker holds each block for 30 s after building it: the kill lands mid-block.
  Child& slow = StartWorker({"--testing-block-delay-ms", "30000"});
  slow.WaitForLog("registered with");
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  const std::smatch building = slow.WaitForLog("building row block (\\d+) of job");
  ASSERT_FALSE(building.empty());
  const std::string block = building[1];
  slow.Stop(SIGKILL);
  ExpectSucceedsBitIdentical(job_id, options);
  const std::string log = server_->Log();
  EXPECT_TRUE(std::regex_search(
      log, std::regex("row block " + block + " \\(rows \\d+\\.\\.\\d+\\) leased again: worker")))
      << "the server log names the block leased again:\n"
      << log;
}

TEST_F(WorkerTest, WorkerJoiningMidJobGetsWork) {
  // The server builds slowly (150 ms per block, about 38 blocks) so the job is mid-rows.
  StartServer({"--testing-block-delay-ms", "150"});
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  Watch(job_id, [](const v1::JobEvent& e) {
    return e.phase() == v1::PHASE_ROWS && e.progress().rows_done() > 0;
  });
  Child& late = StartWorker({});
  ExpectSucceedsBitIdentical(job_id, options);
  EXPECT_GT(CountOf(late.Log(), "sent row block"), 0) << late.Log();
  EXPECT_TRUE(server_->Log().find("worker 1 joined") != std::string::npos);
}

TEST_F(WorkerTest, WrongWorkerTokenOrClientTokenIsRefused) {
  token_ = "client-secret";
  StartServer({"--token", token_, "--worker-token", "worker-secret"});
  Child& wrong = StartWorker({"--worker-token", "not-it"});
  const int status = wrong.Wait();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << wrong.Log();
  EXPECT_NE(wrong.Log().find("UNAUTHENTICATED"), std::string::npos) << wrong.Log();
  // The client token does not register a worker either.
  auto worker_stub =
      v1::Worker::NewStub(grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.AddMetadata("authorization", "Bearer " + token_);
  auto stream = worker_stub->Connect(&context);
  v1::WorkerMessage hello;
  hello.mutable_hello()->set_threads(1);
  stream->Write(hello);
  v1::ServerMessage message;
  EXPECT_FALSE(stream->Read(&message));
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::UNAUTHENTICATED);
  // The right one does.
  Child& right = StartWorker({"--worker-token", "worker-secret"});
  right.WaitForLog("registered with");
}

TEST_F(WorkerTest, BadChecksumDropsTheWorkerAndTheBlockIsBuiltElsewhere) {
  StartServer({});
  auto worker_stub =
      v1::Worker::NewStub(grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.AddMetadata("authorization", "Bearer " + testing::kWorkerToken);
  auto stream = worker_stub->Connect(&context);
  v1::WorkerMessage hello;
  hello.mutable_hello()->set_threads(1);
  hello.mutable_hello()->set_name("forger");
  ASSERT_TRUE(stream->Write(hello));
  v1::ServerMessage message;
  ASSERT_TRUE(stream->Read(&message));
  ASSERT_TRUE(message.has_welcome());
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  ASSERT_TRUE(stream->Read(&message));
  ASSERT_TRUE(message.has_lease());
  const v1::BlockLease& lease = message.lease();
  EXPECT_EQ(lease.job_id(), job_id);
  v1::WorkerMessage forged;
  v1::BlockResult* result = forged.mutable_result();
  result->set_lease_id(lease.lease_id());
  result->set_job_id(lease.job_id());
  result->set_block_index(lease.block_index());
  result->set_first_row(lease.first_row());
  result->set_row_count(lease.row_count());
  result->set_rows_zstd("not zstd at all");
  result->set_sha256(std::string(32, '\0'));
  ASSERT_TRUE(stream->Write(forged));
  while (stream->Read(&message)) {
  }
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::DATA_LOSS);
  ExpectSucceedsBitIdentical(job_id, options);
  const std::string log = server_->Log();
  EXPECT_NE(log.find("(forger) dropped"), std::string::npos) << log;
  EXPECT_NE(log.find("row block " + std::to_string(lease.block_index()) + " (rows"),
            std::string::npos)
      << log;
}

// Two network namespaces joined by a veth pair: the workers are on another "host" than
// the server. Needs root and `ip netns`; skipped with the reason otherwise.
class NetnsWorkerTest : public WorkerTest {
 public:
  void SetUp() override {
    WorkerTest::SetUp();
    const int id = static_cast<int>(getpid() % 200) + 20;
    ns_ = "rfxw" + std::to_string(getpid());
    host_veth_ = "rfxh" + std::to_string(getpid());
    host_ip_ = "10.251." + std::to_string(id) + ".1";
    const std::string ns_ip = "10.251." + std::to_string(id) + ".2";
    const std::string script =
        "ip netns add " + ns_ + " && ip link add " + host_veth_ +
        " type veth peer name rfxn0 netns " + ns_ + " && ip addr add " + host_ip_ + "/24 dev " +
        host_veth_ + " && ip link set " + host_veth_ + " up && ip netns exec " + ns_ +
        " ip addr add " + ns_ip + "/24 dev rfxn0 && ip netns exec " + ns_ +
        " ip link set rfxn0 up && ip netns exec " + ns_ + " ip link set lo up";
    ready_ = std::system((script + " 2>" + dir_ + "/netns.err").c_str()) == 0;
  }
  void TearDown() override {
    workers_.clear();
    server_.reset();
    (void)std::system(("ip link del " + host_veth_ + " 2>/dev/null").c_str());
    (void)std::system(("ip netns del " + ns_ + " 2>/dev/null").c_str());
    WorkerTest::TearDown();
  }

  std::string ns_, host_veth_, host_ip_;
  bool ready_ = false;
};

TEST_F(NetnsWorkerTest, WorkersInAnotherNetworkNamespaceOverVethGiveTheSameResult) {
  if (!ready_) {
    GTEST_SKIP() << "cannot create a network namespace with a veth pair here (needs root and "
                    "`ip netns`/veth support): "
                 << ReadText(dir_ + "/netns.err");
  }
  StartServer({}, host_ip_);
  const std::vector<std::string> prefix = {"ip", "netns", "exec", ns_};
  Child& a = StartWorker({}, prefix);
  Child& b = StartWorker({"--testing-block-delay-ms", "30000"}, prefix);
  a.WaitForLog("registered with");
  b.WaitForLog("registered with");
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  const std::smatch building = b.WaitForLog("building row block (\\d+) of job");
  ASSERT_FALSE(building.empty());
  const std::string block = building[1];
  b.Stop(SIGKILL);
  ExpectSucceedsBitIdentical(job_id, options);
  EXPECT_GT(CountOf(a.Log(), "sent row block"), 0) << a.Log();
  EXPECT_TRUE(std::regex_search(server_->Log(), std::regex("row block " + block +
                                                           " \\(rows \\d+\\.\\.\\d+\\) "
                                                           "leased again")))
      << server_->Log();
}

}  // namespace
}  // namespace radflux
