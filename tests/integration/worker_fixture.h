// The fixture of the worker-node integration tests: radfluxd and `radfluxd --worker` child
// processes on loopback, with logs in a fresh directory per test, and the client calls the
// tests make (upload + submit, watch, result). Shared by worker_test.cc and
// rogue_worker_test.cc. Servers and workers get the worker token kWorkerToken unless a
// test passes its own --worker-token.
#pragma once

#include <fcntl.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
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
#include "tests/integration/radfluxd_path.h"
#include "tests/integration/test_helpers.h"
#include "wire/proto_convert.h"
#include "wire/scene_hash.h"

namespace radflux::testing {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
inline constexpr auto kPatience = std::chrono::seconds(60);  // a guard against hangs, not timing
// The worker token of the tests' servers and workers (workers need one by default).
inline const std::string kWorkerToken = "test-worker-token";

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
  pid_t pid() const { return pid_; }
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

inline v1::SolveOptions Options() {
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

  // radfluxd on `host`:0 with `extra` flags (and --worker-token kWorkerToken unless they
  // name a worker token or allow workers without); returns its HOST:PORT.
  void StartServer(const std::vector<std::string>& extra, const std::string& host = "127.0.0.1") {
    std::vector<std::string> args = {RadfluxdPath(), "--listen",  host + ":0", "--data-dir",
                                     dir_ + "/data", "--threads", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    if (!Names(extra, "--worker-token") && !Names(extra, "--allow-workers-without-token")) {
      args.insert(args.end(), {"--worker-token", kWorkerToken});
    }
    server_ = std::make_unique<Child>(args, dir_ + "/server.log");
    address_ = server_->WaitForLog("radfluxd listening on (\\S+)")[1];
    stub_ =
        v1::Radiosity::NewStub(grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
  }
  // A worker process (with --worker-token kWorkerToken unless `extra` names one); `prefix`
  // runs it through another command (ip netns exec NS).
  Child& StartWorker(const std::vector<std::string>& extra,
                     const std::vector<std::string>& prefix = {}) {
    std::vector<std::string> args = prefix;
    for (const std::string& a : {RadfluxdPath(), std::string("--worker"), std::string("--server"),
                                 address_, std::string("--threads"), std::string("1")}) {
      args.push_back(a);
    }
    args.insert(args.end(), extra.begin(), extra.end());
    if (!Names(extra, "--worker-token")) {
      args.insert(args.end(), {"--worker-token", kWorkerToken});
    }
    const std::string log = dir_ + "/worker" + std::to_string(workers_.size()) + ".log";
    workers_.push_back(std::make_unique<Child>(args, log));
    return *workers_.back();
  }
  std::unique_ptr<grpc::ClientContext> Context() {
    auto context = std::make_unique<grpc::ClientContext>();
    if (!token_.empty()) context->AddMetadata("authorization", "Bearer " + token_);
    return context;
  }
  // True when `flags` holds `flag`.
  static bool Names(const std::vector<std::string>& flags, const std::string& flag) {
    return std::find(flags.begin(), flags.end(), flag) != flags.end();
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

inline int CountOf(const std::string& text, const std::string& needle) {
  int count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

}  // namespace radflux::testing
