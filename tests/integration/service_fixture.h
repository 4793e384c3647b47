// The fixture of the radfluxd integration tests: a fresh data directory per test, a
// radfluxd child process on a loopback port it chose, and the calls the tests make through
// it (upload, submit, watch, result). Shared by service_test.cc and service_mesh_tls_test.cc.
#pragma once

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "radflux/v1/radiosity.grpc.pb.h"
#include "tests/integration/server_process.h"
#include "tests/integration/test_helpers.h"
#include "wire/scene_hash.h"

namespace radflux::testing {

class ServiceFixture : public ::testing::Test {
 public:
  void SetUp() override {
    char pattern[] = "/tmp/radflux_it_XXXXXX";
    data_dir_ = mkdtemp(pattern);
  }
  void TearDown() override {
    server_.reset();
    std::filesystem::remove_all(data_dir_);
  }
  void StartServer(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> flags = {"--threads", "2"};
    flags.insert(flags.end(), extra.begin(), extra.end());
    server_ = std::make_unique<ServerProcess>(data_dir_, flags);
    stub_ = v1::Radiosity::NewStub(
        grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  }
  std::unique_ptr<grpc::ClientContext> Context() {
    auto context = std::make_unique<grpc::ClientContext>();
    if (!token_.empty()) context->AddMetadata("authorization", "Bearer " + token_);
    return context;
  }

  // Uploads OBJ + MTL in small chunks; `declared_extra` bytes more than sent are declared.
  grpc::Status Upload(const std::string& obj, const std::string& mtl, v1::SceneRef* ref,
                      const std::string& sha = "", uint64_t declared_extra = 0) {
    auto context = Context();
    auto writer = stub_->UploadScene(context.get(), ref);
    const std::string data = obj + mtl;
    v1::SceneChunk chunk;
    chunk.mutable_header()->set_name("cornell_box.obj");
    chunk.mutable_header()->set_obj_size(obj.size());
    chunk.mutable_header()->set_mtl_size(mtl.size() + declared_extra);
    chunk.mutable_header()->set_sha256(sha);
    for (size_t at = 0; at < data.size(); at += 1000) {
      chunk.set_data(data.substr(at, 1000));
      if (!writer->Write(chunk)) break;
      chunk.clear_header();
    }
    writer->WritesDone();
    return writer->Finish();
  }

  std::string UploadCornell() {
    v1::SceneRef ref;
    const grpc::Status status = Upload(kObj, kMtl, &ref, SceneContentHash(kObj, kMtl));
    EXPECT_TRUE(status.ok()) << status.error_message();
    return ref.sha256();
  }

  grpc::Status Submit(const v1::SolveOptions& options, v1::Job* job, const std::string& sha,
                      const std::string& request_id = "") {
    v1::SubmitJobRequest request;
    request.set_scene_sha256(sha);
    *request.mutable_options() = options;
    request.set_request_id(request_id);
    return stub_->SubmitJob(Context().get(), request, job);
  }

  // Watches a job until `stop(event)` is true or the stream ends; returns all events.
  std::vector<v1::JobEvent> Watch(const std::string& job_id,
                                  const std::function<bool(const v1::JobEvent&)>& stop = {},
                                  int snapshot_every = 0) {
    v1::WatchJobRequest request;
    request.set_job_id(job_id);
    request.set_snapshot_every(snapshot_every);
    request.set_snapshot_format(v1::SNAPSHOT_FORMAT_FLOAT16);
    return Watch(request, stop);
  }

  // Reads the WatchJob stream of `request` until `stop(event)` or its end; all events.
  std::vector<v1::JobEvent> Watch(const v1::WatchJobRequest& request,
                                  const std::function<bool(const v1::JobEvent&)>& stop) {
    auto context = Context();
    auto reader = stub_->WatchJob(context.get(), request);
    std::vector<v1::JobEvent> events;
    v1::JobEvent event;
    while (reader->Read(&event)) {
      events.push_back(event);
      if (stop && stop(event)) {
        context->TryCancel();
        break;
      }
    }
    reader->Finish();
    return events;
  }

  // The per-patch radiosity of a finished job, exactly as the server sent it.
  grpc::Status Result(const std::string& job_id, std::vector<double>* radiosity,
                      std::string* report = nullptr) {
    v1::GetResultRequest request;
    request.set_job_id(job_id);
    auto context = Context();
    auto reader = stub_->GetResult(context.get(), request);
    v1::ResultChunk chunk;
    while (reader->Read(&chunk)) {
      if (chunk.has_patches()) {
        radiosity->insert(radiosity->end(), chunk.patches().radiosity().begin(),
                          chunk.patches().radiosity().end());
      }
      if (report && chunk.part_case() == v1::ResultChunk::kReportJson)
        *report = chunk.report_json();
    }
    return reader->Finish();
  }

  std::string data_dir_;
  std::string token_;
  std::unique_ptr<ServerProcess> server_;
  std::unique_ptr<v1::Radiosity::Stub> stub_;
};

// Small Cornell-box options: about `patches` patches, 128 rays, a fixed seed.
inline v1::SolveOptions SmallOptions(int64_t patches, const std::string& solver) {
  v1::SolveOptions options;
  options.set_target_patches(patches);
  options.set_rays(128);
  options.set_seed(7);
  options.set_block_size(16);
  options.set_solver(solver);
  return options;
}

// Starts a job, kills the server (kill -9) once the solve has reported iteration 5 (the
// server checkpoints every iteration and sleeps 100 ms after each, so the kill lands mid
// solve although watchers hear of progress up to ~0.5 s late: 250 ms progress throttle,
// 250 ms rounds of writes), restarts it (no delay; both times with `extra` flags) and
// returns the finished job's B. *first_iteration is the first solve iteration the restarted
// server reported: >= 5 proves it resumed from the checkpoint of iteration 4 or later
// (iteration 5's may not be on disk when the kill lands).
inline std::vector<double> KillDuringSolveAndResume(ServiceFixture& t,
                                                    const v1::SolveOptions& options,
                                                    int* first_iteration, std::string* report,
                                                    const std::vector<std::string>& extra = {}) {
  std::vector<std::string> flags = {"--checkpoint-seconds", "0", "--solve-delay-ms", "100"};
  flags.insert(flags.end(), extra.begin(), extra.end());
  t.StartServer(flags);
  const std::string sha = t.UploadCornell();
  v1::Job job;
  EXPECT_TRUE(t.Submit(options, &job, sha).ok());
  const std::vector<v1::JobEvent> before = t.Watch(job.job_id(), [](const v1::JobEvent& e) {
    return e.phase() == v1::PHASE_SOLVE && e.progress().iteration() >= 5;
  });
  EXPECT_NE(before.back().state(), v1::JOB_STATE_SUCCEEDED);
  t.server_->Kill();
  EXPECT_TRUE(std::filesystem::exists(t.data_dir_ + "/jobs/" + job.job_id() + "/checkpoint.rfb"));

  t.StartServer(extra);
  const std::vector<v1::JobEvent> after = t.Watch(job.job_id());
  EXPECT_EQ(after.back().state(), v1::JOB_STATE_SUCCEEDED) << after.back().message();
  *first_iteration = 0;
  for (const v1::JobEvent& e : after) {
    if (e.phase() == v1::PHASE_SOLVE && e.progress().iteration() > 0) {
      *first_iteration = e.progress().iteration();
      break;
    }
  }
  std::vector<double> served;
  EXPECT_TRUE(t.Result(job.job_id(), &served, report).ok());
  return served;
}

}  // namespace radflux::testing
