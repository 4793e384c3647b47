// Integration tests of worker nodes: radfluxd plus `radfluxd --worker` processes on
// loopback (and, where `ip netns` works, in separate network namespaces). Every test starts
// its own processes and stops them; results are compared bit for bit with RunJob.
#include <fcntl.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <thread>

#include "radflux/v1/radiosity.grpc.pb.h"
#include "radflux/v1/worker.grpc.pb.h"
#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "tests/integration/test_helpers.h"
#include "wire/proto_convert.h"
#include "wire/scene_hash.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
constexpr auto kPatience = std::chrono::seconds(60);  // a guard against hangs, not a timing assert

using testing::ExpectBitIdentical;
using testing::InProcess;
using testing::kMtl;
using testing::kObj;
using testing::ReadText;

// A child process with stdout and stderr in a log file.
class Child {
 public:
  Child(std::vector<std::string> args, std::string log) : log_(std::move(log)) {
    pid_ = fork();
    if (pid_ == 0) {
      const int fd = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execvp(argv[0], argv.data());
      _exit(127);
    }
  }
  ~Child() { Stop(SIGTERM); }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  std::string Log() const { return ReadText(log_); }
  // Waits until the log matches `pattern` (or the process exits / patience runs out);
  // returns the first match's groups.
  std::smatch WaitForLog(const std::string& pattern) {
    const std::regex re(pattern);
    const auto until = Clock::now() + kPatience;
    std::smatch match;
    while (Clock::now() < until) {
      static thread_local std::string text;
      text = Log();
      if (std::regex_search(text, match, re)) return match;
      if (Exited()) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ADD_FAILURE() << "no \"" << pattern << "\" in " << log_ << ":\n" << Log();
    return match;
  }
  bool Exited() {
    if (pid_ <= 0) return true;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      exit_status_ = status;
      return true;
    }
    return false;
  }
  // Sends `signal` and reaps; returns the wait status.
  int Stop(int signal) {
    if (pid_ > 0) {
      kill(pid_, signal);
      waitpid(pid_, &exit_status_, 0);
      pid_ = -1;
    }
    return exit_status_;
  }
  // Waits for the process to exit by itself; returns the wait status.
  int Wait() {
    if (pid_ > 0) {
      waitpid(pid_, &exit_status_, 0);
      pid_ = -1;
    }
    return exit_status_;
  }

 private:
  pid_t pid_ = -1;
  int exit_status_ = -1;
  std::string log_;
};

v1::SolveOptions Options() {
  v1::SolveOptions options;
  options.set_target_patches(600);
  options.set_rays(128);
  options.set_seed(11);
  options.set_block_size(16);
  options.set_solver("jacobi");
  return options;
}

class WorkerTest : public ::testing::Test {
 public:
  void SetUp() override {
    char pattern[] = "/tmp/radflux_workers_XXXXXX";
    dir_ = mkdtemp(pattern);
  }
  void TearDown() override {
    workers_.clear();
    server_.reset();
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // radfluxd on `host`:0 with `extra` flags; returns its HOST:PORT.
  void StartServer(const std::vector<std::string>& extra, const std::string& host = "127.0.0.1") {
    std::vector<std::string> args = {RADFLUXD_PATH,  "--listen",  host + ":0", "--data-dir",
                                     dir_ + "/data", "--threads", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    server_ = std::make_unique<Child>(args, dir_ + "/server.log");
    address_ = server_->WaitForLog("radfluxd listening on (\\S+)")[1];
    stub_ =
        v1::Radiosity::NewStub(grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
  }
  // A worker process; `prefix` runs it through another command (ip netns exec NS).
  Child& StartWorker(const std::vector<std::string>& extra,
                     const std::vector<std::string>& prefix = {}) {
    std::vector<std::string> args = prefix;
    for (const std::string& a :
         {std::string(RADFLUXD_PATH), std::string("--worker"), std::string("--server"), address_,
          std::string("--threads"), std::string("1")}) {
      args.push_back(a);
    }
    args.insert(args.end(), extra.begin(), extra.end());
    const std::string log = dir_ + "/worker" + std::to_string(workers_.size()) + ".log";
    workers_.push_back(std::make_unique<Child>(args, log));
    return *workers_.back();
  }
  std::unique_ptr<grpc::ClientContext> Context() {
    auto context = std::make_unique<grpc::ClientContext>();
    if (!token_.empty()) context->AddMetadata("authorization", "Bearer " + token_);
    return context;
  }

  // Uploads the Cornell box and submits a job; returns the job id.
  std::string Submit(const v1::SolveOptions& options) {
    v1::SceneRef ref;
    auto context = Context();
    auto writer = stub_->UploadScene(context.get(), &ref);
    v1::SceneChunk chunk;
    chunk.mutable_header()->set_name("cornell_box.obj");
    chunk.mutable_header()->set_obj_size(kObj.size());
    chunk.mutable_header()->set_mtl_size(kMtl.size());
    chunk.set_data(kObj + kMtl);
    writer->Write(chunk);
    writer->WritesDone();
    const grpc::Status uploaded = writer->Finish();
    EXPECT_TRUE(uploaded.ok()) << uploaded.error_message();
    v1::SubmitJobRequest request;
    request.set_scene_sha256(ref.sha256());
    *request.mutable_options() = options;
    v1::Job job;
    const grpc::Status submitted = stub_->SubmitJob(Context().get(), request, &job);
    EXPECT_TRUE(submitted.ok()) << submitted.error_message();
    return job.job_id();
  }
  // Watches until `stop(event)` or the end of the job; returns the last event.
  v1::JobEvent Watch(const std::string& job_id,
                     const std::function<bool(const v1::JobEvent&)>& stop = {}) {
    v1::WatchJobRequest request;
    request.set_job_id(job_id);
    auto context = Context();
    auto reader = stub_->WatchJob(context.get(), request);
    v1::JobEvent event;
    while (reader->Read(&event)) {
      if (stop && stop(event)) {
        context->TryCancel();
        break;
      }
    }
    reader->Finish();
    return event;
  }
  std::vector<double> Result(const std::string& job_id) {
    v1::GetResultRequest request;
    request.set_job_id(job_id);
    auto context = Context();
    auto reader = stub_->GetResult(context.get(), request);
    std::vector<double> radiosity;
    v1::ResultChunk chunk;
    while (reader->Read(&chunk)) {
      if (chunk.has_patches()) {
        radiosity.insert(radiosity.end(), chunk.patches().radiosity().begin(),
                         chunk.patches().radiosity().end());
      }
    }
    const grpc::Status status = reader->Finish();
    EXPECT_TRUE(status.ok()) << status.error_message();
    return radiosity;
  }
  // Runs the job to the end and checks it against RunJob, bit for bit.
  void ExpectSucceedsBitIdentical(const std::string& job_id, const v1::SolveOptions& options) {
    const v1::JobEvent last = Watch(job_id);
    ASSERT_EQ(last.state(), v1::JOB_STATE_SUCCEEDED) << last.message();
    const std::vector<double> served = Result(job_id);
    ExpectBitIdentical(served, InProcess(options), "the result differs from RunJob");
  }

  std::string dir_;
  std::string address_;
  std::string token_;
  std::unique_ptr<Child> server_;
  std::vector<std::unique_ptr<Child>> workers_;
  std::unique_ptr<v1::Radiosity::Stub> stub_;
};

int CountOf(const std::string& text, const std::string& needle) {
  int count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

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
