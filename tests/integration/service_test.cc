// Integration tests of radfluxd over loopback gRPC: each test starts its own server on a
// port the server picks, with a fresh data directory.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "radflux/v1/radiosity.grpc.pb.h"
#include "solver/pipeline.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"
#include "wire/proto_convert.h"
#include "wire/scene_hash.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;
using testing::ExpectBitIdentical;
using testing::InProcess;
using testing::kMtl;
using testing::kObj;
using testing::ReadText;
using testing::SmallOptions;

class ServiceTest : public testing::ServiceFixture {};

TEST_F(ServiceTest, SubmitWatchResultEqualsInProcessRunJobBitForBit) {
  StartServer();
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(300, "cg");
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha, "req-1").ok());
  v1::Job again;
  ASSERT_TRUE(Submit(options, &again, sha, "req-1").ok());
  EXPECT_EQ(job.job_id(), again.job_id()) << "a retried submit must return the same job";

  const std::vector<v1::JobEvent> events = Watch(job.job_id(), {}, /*snapshot_every=*/1);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  uint64_t last = 0;
  int64_t patches = 0;
  bool saw_snapshot = false;
  for (const v1::JobEvent& e : events) {
    if (e.has_snapshot()) {
      saw_snapshot = true;
      EXPECT_EQ(e.sequence(), last) << "a snapshot carries the sequence it follows";
      // Its header is the watcher's own, its snapshot field the bytes shared by all.
      EXPECT_EQ(e.job_id(), job.job_id());
      EXPECT_EQ(e.state(), v1::JOB_STATE_RUNNING);
      EXPECT_EQ(e.phase(), v1::PHASE_SOLVE);
      EXPECT_EQ(e.snapshot().patch_count(), static_cast<uint64_t>(patches));
      EXPECT_TRUE(SnapshotValues(e.snapshot()).ok());
      continue;
    }
    EXPECT_EQ(e.sequence(), last + 1);
    EXPECT_EQ(e.job_id(), job.job_id());
    last = e.sequence();
    if (e.phase() == v1::PHASE_ROWS) patches = std::max(patches, e.progress().rows_total());
  }
  EXPECT_GT(patches, 250) << "rows progress reports the patch count (about 300 asked)";
  EXPECT_TRUE(saw_snapshot);

  // Resuming after the last sequence seen misses nothing and ends at once.
  v1::WatchJobRequest resume;
  resume.set_job_id(job.job_id());
  resume.set_after_sequence(last - 1);
  auto context = Context();
  auto reader = stub_->WatchJob(context.get(), resume);
  v1::JobEvent event;
  ASSERT_TRUE(reader->Read(&event));
  EXPECT_EQ(event.sequence(), last);
  EXPECT_FALSE(reader->Read(&event));
  EXPECT_TRUE(reader->Finish().ok());

  std::vector<double> served;
  std::string report;
  const grpc::Status status = Result(job.job_id(), &served, &report);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ExpectBitIdentical(served, InProcess(options));

  // report_only: the header (with the counts) and the same report, no mesh and no B.
  v1::GetResultRequest request;
  request.set_job_id(job.job_id());
  request.set_report_only(true);
  auto result_context = Context();
  auto result_reader = stub_->GetResult(result_context.get(), request);
  std::vector<v1::ResultChunk> chunks;
  for (v1::ResultChunk chunk; result_reader->Read(&chunk);) chunks.push_back(chunk);
  ASSERT_TRUE(result_reader->Finish().ok());
  ASSERT_EQ(chunks.size(), 2u);
  EXPECT_EQ(chunks[0].header().patch_count(), served.size() / 3);
  EXPECT_EQ(chunks[0].header().job().job_id(), job.job_id());
  EXPECT_EQ(chunks[1].report_json(), report);
}

// A job whose faces are grouped (more faces than --patches) takes the mesh its admission
// built to count its unknowns (LoadedScene::TakeMesh) instead of meshing again: the result is
// still RunJob's, bit for bit.
TEST_F(ServiceTest, GroupedJobTakesTheMeshItsAdmissionCountedBitForBit) {
  StartServer();
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(8, "gauss_seidel");  // 17 faces: grouped
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha).ok());
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  std::vector<double> served;
  std::string report;
  ASSERT_TRUE(Result(job.job_id(), &served, &report).ok());
  ExpectBitIdentical(served, InProcess(options));
  const nlohmann::json r = nlohmann::json::parse(report);
  EXPECT_TRUE(r["mesh"]["unknowns"]["grouped"].get<bool>()) << r["mesh"].dump();
}

// Progress events are throttled (at most one per 50 ms, the newest): the newest of each
// phase is never lost, whatever was coalesced before it.
TEST_F(ServiceTest, ThrottledProgressEndsEachPhaseWithItsNewestEvent) {
  StartServer();
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(1200, "jacobi");
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha).ok());
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  const v1::JobEvent* last_rows = nullptr;
  const v1::JobEvent* last_solve = nullptr;
  bool solving = false, finished = false;  // the SOLVE phase / the final event was seen
  for (const v1::JobEvent& e : events) {
    if (!e.has_progress()) {
      solving = solving || e.phase() == v1::PHASE_SOLVE;
      finished = finished || e.state() == v1::JOB_STATE_SUCCEEDED;
      continue;
    }
    EXPECT_FALSE(finished) << "a progress event after the final event";
    if (e.phase() == v1::PHASE_ROWS) {
      EXPECT_FALSE(solving) << "a rows progress event after the SOLVE phase began";
      last_rows = &e;
    } else {
      EXPECT_TRUE(solving) << "a solve progress event before the SOLVE phase began";
      last_solve = &e;
    }
  }
  ASSERT_NE(last_rows, nullptr);
  EXPECT_EQ(last_rows->progress().rows_done(), last_rows->progress().rows_total());
  EXPECT_GT(last_rows->progress().rows_total(), 1100);
  std::string report;
  std::vector<double> served;
  ASSERT_TRUE(Result(job.job_id(), &served, &report).ok());
  EXPECT_EQ(last_solve->progress().iteration(),
            nlohmann::json::parse(report)["solve"]["iterations"].get<int>());
}

TEST_F(ServiceTest, CancelMidRowsEndsCancelledAndCleansFiles) {
  // 20 ms a row block (188 blocks): the cancel lands mid-rows however fast the machine is.
  StartServer({"--testing-block-delay-ms", "20"});
  const std::string sha = UploadCornell();
  v1::SolveOptions options = SmallOptions(3000, "cg");
  options.set_rays(512);
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha).ok());
  Watch(job.job_id(), [](const v1::JobEvent& e) { return e.progress().rows_done() > 0; });
  v1::CancelJobRequest cancel;
  cancel.set_job_id(job.job_id());
  v1::Job cancelled;
  ASSERT_TRUE(stub_->CancelJob(Context().get(), cancel, &cancelled).ok());
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().state(), v1::JOB_STATE_CANCELLED);
  std::vector<double> served;
  EXPECT_EQ(Result(job.job_id(), &served).error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  size_t files = 0;
  for ([[maybe_unused]] const auto& f : fs::directory_iterator(data_dir_ + "/jobs/" + job.job_id()))
    ++files;
  EXPECT_EQ(files, 0u) << "a cancelled job's row blocks and checkpoint are removed";
}

TEST_F(ServiceTest, BadInputGetsTheRightStatusAndTheServerKeepsServing) {
  StartServer({"--max-patches", "100000"});
  v1::SceneRef ref;
  grpc::Status s = Upload(kObj, kMtl, &ref, "", /*declared_extra=*/100);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::DATA_LOSS);
  EXPECT_NE(s.error_message().find("truncated"), std::string::npos) << s.error_message();

  s = Upload(kObj, kMtl, &ref, std::string(64, 'a'));
  EXPECT_EQ(s.error_code(), grpc::StatusCode::DATA_LOSS);
  EXPECT_NE(s.error_message().find("hashes to"), std::string::npos) << s.error_message();

  s = Upload("v 0 0 0\nv 1 0 0\nf 1 2 99\n", "", &ref);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << s.error_message();
  EXPECT_FALSE(s.error_message().empty());

  const std::string sha = UploadCornell();
  v1::Job job;
  v1::SolveOptions options = SmallOptions(300, "cg");
  options.set_rays(-5);
  s = Submit(options, &job, sha);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << s.error_message();
  options = SmallOptions(300, "no_such_solver");
  s = Submit(options, &job, sha);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(s.error_message().find("no_such_solver"), std::string::npos);
  s = Submit(SmallOptions(1'000'000'000'000, "cg"), &job, sha);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << s.error_message();
  EXPECT_NE(s.error_message().find("--max-patches"), std::string::npos);
  s = Submit(SmallOptions(300, "cg"), &job, std::string(64, '0'));
  EXPECT_EQ(s.error_code(), grpc::StatusCode::NOT_FOUND);

  std::vector<double> served;
  EXPECT_EQ(Result("job-unknown", &served).error_code(), grpc::StatusCode::NOT_FOUND);
  v1::ListJobsResponse list;
  EXPECT_TRUE(stub_->ListJobs(Context().get(), {}, &list).ok());
  EXPECT_EQ(list.jobs_size(), 0) << "refused submits leave no job behind";
}

TEST_F(ServiceTest, CorruptOversizeAndAbsurdInputGetTheirStatusAndTheServerKeepsServing) {
  StartServer({"--max-upload", "4096"});
  v1::SceneRef ref;
  // A chunk altered in transit: the content no longer hashes to the declared address.
  std::string corrupt = kObj;
  corrupt[1500] ^= 0x20;
  grpc::Status s = Upload(corrupt, kMtl, &ref, SceneContentHash(kObj, kMtl));
  EXPECT_EQ(s.error_code(), grpc::StatusCode::DATA_LOSS);
  EXPECT_NE(s.error_message().find("hashes to " + SceneContentHash(corrupt, kMtl)),
            std::string::npos)
      << s.error_message();

  // Beyond --max-upload (4096 bytes): refused on the header, before the data.
  const std::string big = kObj + "#" + std::string(4000, 'x') + "\n";
  s = Upload(big, kMtl, &ref, SceneContentHash(big, kMtl));
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(s.error_message().find("upload limit of 4096 bytes (--max-upload)"), std::string::npos)
      << s.error_message();

  // A small scene that fits, then absurd options, each refused with the option named.
  const std::string obj =
      "usemtl lamp\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
      "usemtl wall\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 5 8 7 6\n";
  const std::string mtl = "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\nnewmtl wall\nKd 0.8 0.8 0.8\n";
  s = Upload(obj, mtl, &ref);
  ASSERT_TRUE(s.ok()) << s.error_message();
  const std::string sha = ref.sha256();
  struct Case {
    std::function<void(v1::SolveOptions&)> set;
    std::string named;
  };
  const std::vector<Case> cases = {
      {[](v1::SolveOptions& o) { o.set_tolerance(std::nan("")); }, "--tolerance"},
      {[](v1::SolveOptions& o) { o.set_tolerance(-1); }, "--tolerance"},
      {[](v1::SolveOptions& o) { o.set_max_iterations(-1); }, "--max-iterations"},
      {[](v1::SolveOptions& o) { o.set_target_patches(-5); }, "--patches"},
      {[](v1::SolveOptions& o) {
         o.set_max_edge(INFINITY);
         o.clear_target_patches();
       },
       "--max-edge"},
      {[](v1::SolveOptions& o) { o.set_cutoff(2); }, "--cutoff"},
      {[](v1::SolveOptions& o) { o.set_block_size(-1); }, "block size"},
      {[](v1::SolveOptions& o) {
         o.set_form_factor_method("hemicube");
         o.set_hemicube_res(3);
       },
       "--hemicube-res"},
  };
  v1::Job job;
  for (const Case& c : cases) {
    v1::SolveOptions options = SmallOptions(10, "cg");
    c.set(options);
    s = Submit(options, &job, sha);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.named;
    EXPECT_NE(s.error_message().find(c.named), std::string::npos) << s.error_message();
  }

  // Absurd watch requests: negative cadence, out-of-range or repeated bands.
  const auto expect_watch_refused = [&](const v1::WatchJobRequest& request,
                                        const std::string& named) {
    auto context = Context();
    auto reader = stub_->WatchJob(context.get(), request);
    v1::JobEvent event;
    EXPECT_FALSE(reader->Read(&event));
    s = reader->Finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(s.error_message().find(named), std::string::npos) << s.error_message();
  };
  for (const std::vector<int>& bands : {std::vector<int>{7}, std::vector<int>{-1}, {0, 0}}) {
    v1::WatchJobRequest request;
    request.set_job_id("job-unknown");
    for (int b : bands) request.add_bands(b);
    expect_watch_refused(request, "bands must be");
  }
  {
    v1::WatchJobRequest request;
    request.set_job_id("job-unknown");
    request.set_snapshot_every(-3);
    expect_watch_refused(request, "snapshot_every");
  }

  // The server keeps serving: a valid job runs to SUCCEEDED and is the only job listed.
  ASSERT_TRUE(Submit(SmallOptions(10, "cg"), &job, sha).ok());
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  v1::ListJobsResponse list;
  ASSERT_TRUE(stub_->ListJobs(Context().get(), {}, &list).ok());
  EXPECT_EQ(list.jobs_size(), 1);
}

TEST_F(ServiceTest, MemoryLimitRefusesBeforeAnyWork) {
  StartServer({"--max-memory", "1000"});
  const std::string sha = UploadCornell();
  v1::Job job;
  const grpc::Status s = Submit(SmallOptions(300, "cg"), &job, sha);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(s.error_message().find("--max-memory"), std::string::npos) << s.error_message();
}

TEST_F(ServiceTest, BearerTokenIsRequiredWhenConfigured) {
  StartServer({"--token", "s3cret"});
  v1::ListJobsResponse list;
  grpc::Status s = stub_->ListJobs(Context().get(), {}, &list);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_NE(s.error_message().find("missing"), std::string::npos);
  token_ = "wrong";
  s = stub_->ListJobs(Context().get(), {}, &list);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_NE(s.error_message().find("invalid"), std::string::npos);
  v1::SceneRef ref;
  EXPECT_EQ(Upload(kObj, kMtl, &ref).error_code(), grpc::StatusCode::UNAUTHENTICATED);
  token_ = "s3cret";
  EXPECT_TRUE(stub_->ListJobs(Context().get(), {}, &list).ok());
  EXPECT_FALSE(UploadCornell().empty());
}

TEST_F(ServiceTest, TlsServerCertificate) {
  const std::string cert = data_dir_ + "/cert.pem", key = data_dir_ + "/key.pem";
  const std::string command =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost "
      "-addext subjectAltName=DNS:localhost -keyout " +
      key + " -out " + cert + " 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  StartServer({"--tls-cert", cert, "--tls-key", key});
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = ReadText(cert);
  grpc::ChannelArguments args;
  args.SetSslTargetNameOverride("localhost");
  auto stub = v1::Radiosity::NewStub(
      grpc::CreateCustomChannel(server_->address(), grpc::SslCredentials(ssl), args));
  v1::ListJobsResponse list;
  grpc::ClientContext context;
  EXPECT_TRUE(stub->ListJobs(&context, {}, &list).ok());
  // A plaintext client cannot talk to it.
  grpc::ClientContext plain_context;
  const grpc::Status plain = stub_->ListJobs(&plain_context, {}, &list);
  EXPECT_EQ(plain.error_code(), grpc::StatusCode::UNAVAILABLE);
}

}  // namespace
}  // namespace radflux
