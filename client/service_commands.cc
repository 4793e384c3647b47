#include "client/service_commands.h"

#include <grpcpp/grpcpp.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "client/job_flags.h"
#include "radflux/v1/radiosity.grpc.pb.h"
#include "server/proto_convert.h"
#include "server/scene_hash.h"

namespace radflux::cli {
namespace {

namespace fs = std::filesystem;

struct ConnectionFlags {
  std::string server = "localhost:50051";
  std::string token;
  std::string tls_ca;
};

// A failed call as one line; UNAVAILABLE means nobody answered.
int Report(const grpc::Status& status, const ConnectionFlags& c) {
  if (status.error_code() == grpc::StatusCode::UNAVAILABLE) {
    std::cerr << "radflux: cannot reach radfluxd at " << c.server << " (" << status.error_message()
              << ")\n";
  } else {
    std::cerr << "radflux: server refused: "
              << absl::StatusCodeToString(static_cast<absl::StatusCode>(status.error_code()))
              << ": " << status.error_message() << "\n";
  }
  return 1;
}

bool ReadFile(const std::string& path, std::string* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::stringstream buffer;
  buffer << in.rdbuf();
  *out = buffer.str();
  return true;
}

class Client {
 public:
  explicit Client(const ConnectionFlags& c) : flags_(c) {
    std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
    if (!c.tls_ca.empty()) {
      grpc::SslCredentialsOptions ssl;
      if (!ReadFile(c.tls_ca, &ssl.pem_root_certs)) std::cerr << "radflux: cannot read --tls-ca " << c.tls_ca << "\n";
      credentials = grpc::SslCredentials(ssl);
    }
    stub_ = v1::Radiosity::NewStub(grpc::CreateChannel(c.server, credentials));
  }
  std::unique_ptr<grpc::ClientContext> Context() const {
    auto context = std::make_unique<grpc::ClientContext>();
    if (!flags_.token.empty()) context->AddMetadata("authorization", "Bearer " + flags_.token);
    return context;
  }
  v1::Radiosity::Stub& stub() { return *stub_; }
  const ConnectionFlags& flags() const { return flags_; }

 private:
  ConnectionFlags flags_;
  std::unique_ptr<v1::Radiosity::Stub> stub_;
};

// The MTL text of an OBJ: its mtllib file beside it, else SCENE.mtl, else empty.
std::string FindMtl(const std::string& obj_path, const std::string& obj) {
  std::istringstream lines(obj);
  std::string line, mtl;
  while (std::getline(lines, line)) {
    if (line.rfind("mtllib ", 0) == 0) {
      std::string name = line.substr(7);
      while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
      if (ReadFile((fs::path(obj_path).parent_path() / name).string(), &mtl)) return mtl;
    }
  }
  ReadFile(fs::path(obj_path).replace_extension(".mtl").string(), &mtl);
  return mtl;
}

grpc::Status UploadScene(Client& client, const std::string& path, std::string* sha) {
  std::string obj;
  if (!ReadFile(path, &obj)) return grpc::Status(grpc::StatusCode::NOT_FOUND, "cannot read " + path);
  const std::string mtl = FindMtl(path, obj);
  v1::SceneRef ref;
  auto context = client.Context();
  auto writer = client.stub().UploadScene(context.get(), &ref);
  v1::SceneChunk chunk;
  chunk.mutable_header()->set_name(fs::path(path).filename().string());
  chunk.mutable_header()->set_obj_size(obj.size());
  chunk.mutable_header()->set_mtl_size(mtl.size());
  chunk.mutable_header()->set_sha256(SceneContentHash(obj, mtl));
  const std::string data = obj + mtl;
  constexpr size_t kChunk = 1 << 20;
  for (size_t at = 0; at == 0 || at < data.size(); at += kChunk) {
    chunk.set_data(data.substr(at, kChunk));
    if (!writer->Write(chunk)) break;
    chunk.clear_header();
  }
  writer->WritesDone();
  grpc::Status status = writer->Finish();
  *sha = ref.sha256();
  return status;
}

// Streams a job's events to stderr until it ends; returns 0 when it SUCCEEDED.
int WatchJob(Client& client, const std::string& job_id, const std::string& snapshots_dir) {
  v1::WatchJobRequest request;
  request.set_job_id(job_id);
  if (!snapshots_dir.empty()) {
    request.set_snapshot_every(1);
    fs::create_directories(snapshots_dir);
  }
  auto context = client.Context();
  auto reader = client.stub().WatchJob(context.get(), request);
  v1::JobEvent event;
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  std::string message;
  while (reader->Read(&event)) {
    if (event.has_snapshot()) {
      absl::StatusOr<std::vector<float>> values = SnapshotValues(event.snapshot());
      if (!values.ok()) continue;
      std::ofstream out(fs::path(snapshots_dir) /
                        ("snapshot_" + std::to_string(event.snapshot().iteration()) + ".csv"));
      out << "patch,r,g,b\n";
      const size_t bands = static_cast<size_t>(event.snapshot().bands_size());
      for (size_t p = 0; p < event.snapshot().patch_count(); ++p) {
        out << p;
        for (size_t b = 0; b < bands; ++b) out << "," << (*values)[p * bands + b];
        out << "\n";
      }
      continue;
    }
    state = event.state();
    message = event.message();
    const v1::Progress& p = event.progress();
    std::cerr << "[" << event.sequence() << "] " << v1::JobState_Name(event.state()) << " "
              << v1::Phase_Name(event.phase());
    if (event.phase() == v1::PHASE_ROWS && p.rows_total() > 0) {
      std::cerr << " rows " << p.rows_done() << "/" << p.rows_total() << " ("
                << static_cast<int64_t>(p.rays_per_second()) << " rays/s, ETA "
                << static_cast<int>(p.eta_seconds()) << " s)";
    }
    if (event.phase() == v1::PHASE_SOLVE && p.iteration() > 0) {
      std::cerr << " iteration " << p.iteration() << " residual " << p.residual();
    }
    if (!message.empty()) std::cerr << ": " << message;
    std::cerr << "\n";
  }
  const grpc::Status status = reader->Finish();
  if (!status.ok()) return Report(status, client.flags());
  if (state != v1::JOB_STATE_SUCCEEDED) {
    std::cerr << "radflux: job " << job_id << " ended " << v1::JobState_Name(state)
              << (message.empty() ? "" : ": " + message) << "\n";
    return 1;
  }
  return 0;
}

struct ResultFlags {
  std::string job_id, patch_values, report;
};

int GetResult(Client& client, const ResultFlags& flags) {
  v1::GetResultRequest request;
  request.set_job_id(flags.job_id);
  auto context = client.Context();
  auto reader = client.stub().GetResult(context.get(), request);
  v1::ResultChunk chunk;
  std::vector<double> radiosity;
  std::vector<uint32_t> faces;
  std::string report;
  while (reader->Read(&chunk)) {
    if (chunk.has_patches()) {
      radiosity.insert(radiosity.end(), chunk.patches().radiosity().begin(),
                       chunk.patches().radiosity().end());
      faces.insert(faces.end(), chunk.patches().source_face().begin(),
                   chunk.patches().source_face().end());
    }
    if (chunk.part_case() == v1::ResultChunk::kReportJson) report = chunk.report_json();
  }
  const grpc::Status status = reader->Finish();
  if (!status.ok()) return Report(status, client.flags());
  if (!flags.patch_values.empty()) {
    std::ofstream out(flags.patch_values);
    out.precision(17);
    out << "patch,face,r,g,b\n";
    for (size_t p = 0; p < faces.size(); ++p) {
      out << p << "," << faces[p] << "," << radiosity[3 * p] << "," << radiosity[3 * p + 1] << ","
          << radiosity[3 * p + 2] << "\n";
    }
    if (!out) return std::cerr << "radflux: cannot write " << flags.patch_values << "\n", 1;
  }
  if (!flags.report.empty()) {
    std::ofstream out(flags.report);
    out << report << "\n";
    if (!out) return std::cerr << "radflux: cannot write " << flags.report << "\n", 1;
  }
  std::cout << faces.size() << " patches\n";
  return 0;
}

// Adds the connection flags to `command` (and to the top level once), bound to `c`.
void AddConnectionFlags(CLI::App& command, ConnectionFlags& c) {
  command.add_option("--server", c.server, "radfluxd address HOST:PORT");
  command.add_option("--token", c.token, "bearer token");
  command.add_option("--tls-ca", c.tls_ca, "PEM CA certificate: connect with TLS");
}

}  // namespace

void AddServiceCommands(CLI::App& app, int& exit_code) {
  auto c = std::make_shared<ConnectionFlags>();
  if (!app.get_option_no_throw("--server")) AddConnectionFlags(app, *c);

  auto* submit = app.add_subcommand("submit", "upload a scene and submit a job to radfluxd");
  auto job_flags = std::make_shared<JobFlags>();
  auto scene = std::make_shared<std::string>();
  auto watch = std::make_shared<bool>(false);
  auto request_id = std::make_shared<std::string>();
  submit->add_option("scene", *scene, "OBJ file (its MTL is found via mtllib)")->required();
  AddJobFlags(*submit, *job_flags);
  submit->add_flag("--watch", *watch, "watch the job until it ends");
  submit->add_option("--request-id", *request_id, "idempotency key: a retry returns the same job");
  AddConnectionFlags(*submit, *c);
  submit->callback([=, &exit_code] {
    absl::StatusOr<JobOptions> options = ToJobOptions(*job_flags);
    if (!options.ok()) {
      std::cerr << "radflux: " << options.status().message() << "\n";
      exit_code = 1;
      return;
    }
    Client client(*c);
    v1::SubmitJobRequest request;
    grpc::Status status = UploadScene(client, *scene, request.mutable_scene_sha256());
    if (!status.ok()) return void(exit_code = Report(status, *c));
    *request.mutable_options() = ToProto(*options);
    request.set_request_id(*request_id);
    v1::Job job;
    status = client.stub().SubmitJob(client.Context().get(), request, &job);
    if (!status.ok()) return void(exit_code = Report(status, *c));
    std::cerr << "submitted " << job.job_id() << " (scene " << request.scene_sha256().substr(0, 12)
              << ")\n";
    if (*watch) exit_code = WatchJob(client, job.job_id(), "");
    std::cout << job.job_id() << std::endl;
  });

  auto* watch_cmd = app.add_subcommand("watch", "follow a job's progress");
  auto job_id = std::make_shared<std::string>();
  auto snapshots = std::make_shared<std::string>();
  watch_cmd->add_option("job", *job_id, "job id")->required();
  watch_cmd->add_option("--snapshots", *snapshots, "write each snapshot as CSV into DIR");
  AddConnectionFlags(*watch_cmd, *c);
  watch_cmd->callback([=, &exit_code] {
    Client client(*c);
    exit_code = WatchJob(client, *job_id, *snapshots);
  });

  auto* result = app.add_subcommand("result", "fetch a finished job's result");
  auto result_flags = std::make_shared<ResultFlags>();
  result->add_option("job", result_flags->job_id, "job id")->required();
  result->add_option("--patch-values", result_flags->patch_values, "per-patch B as CSV");
  result->add_option("--report", result_flags->report, "the job's report as JSON");
  AddConnectionFlags(*result, *c);
  result->callback([=, &exit_code] {
    Client client(*c);
    exit_code = GetResult(client, *result_flags);
  });

  auto* cancel = app.add_subcommand("cancel", "cancel a queued or running job");
  auto cancel_id = std::make_shared<std::string>();
  cancel->add_option("job", *cancel_id, "job id")->required();
  AddConnectionFlags(*cancel, *c);
  cancel->callback([=, &exit_code] {
    Client client(*c);
    v1::CancelJobRequest request;
    request.set_job_id(*cancel_id);
    v1::Job job;
    const grpc::Status status = client.stub().CancelJob(client.Context().get(), request, &job);
    if (!status.ok()) return void(exit_code = Report(status, *c));
    std::cout << job.job_id() << " " << v1::JobState_Name(job.state()) << "\n";
  });

  auto* list = app.add_subcommand("list", "list jobs, newest first");
  auto page_size = std::make_shared<int>(100);
  list->add_option("--limit", *page_size, "at most this many jobs");
  AddConnectionFlags(*list, *c);
  list->callback([=, &exit_code] {
    Client client(*c);
    v1::ListJobsRequest request;
    request.set_page_size(*page_size);
    v1::ListJobsResponse response;
    const grpc::Status status = client.stub().ListJobs(client.Context().get(), request, &response);
    if (!status.ok()) return void(exit_code = Report(status, *c));
    for (const v1::Job& job : response.jobs()) {
      std::cout << job.job_id() << "  " << v1::JobState_Name(job.state()) << "  "
                << v1::Phase_Name(job.phase()) << "  patches " << job.patches() << "  "
                << job.message() << "\n";
    }
  });
}

}  // namespace radflux::cli
