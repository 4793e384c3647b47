#include "client/service_commands.h"

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "client/exit_status.h"
#include "client/job_flags.h"
#include "client/output_flags.h"
#include "radflux/v1/radiosity.grpc.pb.h"
#include "server/grpc_credentials.h"
#include "server/proto_convert.h"
#include "server/scene_hash.h"
#include "server/scene_stream.h"
#include "server/stored_scene.h"
#include "solver/mesh/subdivide.h"
#include "solver/scene/validation.h"

namespace radflux::cli {
namespace {

namespace fs = std::filesystem;

struct ConnectionFlags {
  std::string server = "localhost:50051";
  std::string token;
  std::string tls_ca;
  std::string tls_cert, tls_key;  // client certificate, for a server with --tls-client-ca
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

class Client {
 public:
  explicit Client(const ConnectionFlags& c) : flags_(c) {
    std::shared_ptr<grpc::ChannelCredentials> credentials =
        ChannelCredentialsFromFile(c.tls_ca, c.tls_cert, c.tls_key);
    if (!credentials) {  // warn, and go on with TLS trusting the default roots
      std::cerr << "radflux: cannot read --tls-ca " << c.tls_ca << " / --tls-cert " << c.tls_cert
                << " / --tls-key " << c.tls_key << "\n";
      credentials = grpc::SslCredentials(grpc::SslCredentialsOptions());
    }
    // A dropped connection is retried within a second (gRPC's default backoff grows to
    // 120 s), so that a watch resumes soon after a server restart. (Not the "min" backoff:
    // gRPC uses it as the timeout of each connection attempt, 20 s by default.)
    grpc::ChannelArguments arguments;
    arguments.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 100);
    arguments.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 1000);
    channel_ = grpc::CreateCustomChannel(c.server, credentials, arguments);
    stub_ = v1::Radiosity::NewStub(channel_);
  }
  std::unique_ptr<grpc::ClientContext> Context() const {
    auto context = std::make_unique<grpc::ClientContext>();
    if (!flags_.token.empty()) context->AddMetadata("authorization", "Bearer " + flags_.token);
    return context;
  }
  v1::Radiosity::Stub& stub() { return *stub_; }
  const ConnectionFlags& flags() const { return flags_; }
  // Waits until the channel is connected (reconnecting as needed), at most until `deadline`.
  bool WaitForConnected(std::chrono::system_clock::time_point deadline) {
    return channel_->WaitForConnected(deadline);
  }

 private:
  ConnectionFlags flags_;
  std::shared_ptr<grpc::Channel> channel_;
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

// An OBJ scene file as the client sends it: its text, its MTL text and their content address.
struct SceneFile {
  std::string name, obj, mtl, sha256;
};

absl::StatusOr<SceneFile> ReadSceneFile(const std::string& path) {
  SceneFile scene;
  if (!ReadFile(path, &scene.obj)) return absl::NotFoundError("cannot read " + path);
  scene.mtl = FindMtl(path, scene.obj);
  scene.name = fs::path(path).filename().string();
  scene.sha256 = SceneContentHash(scene.obj, scene.mtl);
  return scene;
}

grpc::Status UploadScene(Client& client, const SceneFile& scene) {
  v1::SceneRef ref;
  auto context = client.Context();
  auto writer = client.stub().UploadScene(context.get(), &ref);
  v1::SceneChunk chunk;
  chunk.mutable_header()->set_name(scene.name);
  chunk.mutable_header()->set_obj_size(scene.obj.size());
  chunk.mutable_header()->set_mtl_size(scene.mtl.size());
  chunk.mutable_header()->set_sha256(scene.sha256);
  const std::string data = scene.obj + scene.mtl;
  constexpr size_t kChunk = 1 << 20;
  for (size_t at = 0; at == 0 || at < data.size(); at += kChunk) {
    chunk.set_data(data.substr(at, kChunk));
    if (!writer->Write(chunk)) break;
    chunk.clear_header();
  }
  writer->WritesDone();
  return writer->Finish();
}

// Submits `request` for `scene`: by its content address first, so that a scene the server
// already holds is not sent again (one call instead of two); uploaded, and submitted again,
// only when the server answers NOT_FOUND.
grpc::Status SubmitScene(Client& client, const SceneFile& scene, v1::SubmitJobRequest& request,
                         v1::Job* job) {
  request.set_scene_sha256(scene.sha256);
  grpc::Status status = client.stub().SubmitJob(client.Context().get(), request, job);
  if (status.error_code() != grpc::StatusCode::NOT_FOUND) return status;
  if (status = UploadScene(client, scene); !status.ok()) return status;
  return client.stub().SubmitJob(client.Context().get(), request, job);
}

// A job's scene fetched from the server (GetScene), re-loaded and re-meshed with the job's
// options: with B, all that WriteOutputs needs. Meshing is deterministic, so this is the
// mesh the server solved on (GetResult checks it against the mesh it streams).
struct JobGeometry {
  Scene scene;
  PatchMesh mesh;
};

absl::Status FetchJob(Client& client, const std::string& job_id, v1::Job* job) {
  v1::GetJobRequest request;
  request.set_job_id(job_id);
  return FromGrpcStatus(client.stub().GetJob(client.Context().get(), request, job));
}

absl::StatusOr<JobGeometry> FetchGeometry(Client& client, const v1::Job& job) {
  v1::GetSceneRequest request;
  request.set_sha256(job.scene_sha256());
  auto context = client.Context();
  auto reader = client.stub().GetScene(context.get(), request);
  absl::StatusOr<StoredScene> stored = ReadSceneChunks(*reader, job.scene_sha256());
  if (!stored.ok()) return stored.status();
  absl::StatusOr<JobOptions> options = FromProto(job.options());
  if (!options.ok()) return options.status();
  JobGeometry geometry;
  absl::StatusOr<Scene> scene = LoadStoredScene(*stored);
  if (!scene.ok()) return scene.status();
  geometry.scene = *std::move(scene);
  if (absl::Status s = ValidateScene(geometry.scene); !s.ok()) return s;
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(geometry.scene, options->mesh);
  if (!mesh.ok()) return mesh.status();
  geometry.mesh = *std::move(mesh);
  return geometry;
}

// One line on stderr for a failure; server errors name the server, local ones do not.
int Fail(const absl::Status& status, const ConnectionFlags& c) {
  if (status.code() == absl::StatusCode::kUnavailable ||
      status.code() == absl::StatusCode::kUnauthenticated ||
      status.code() == absl::StatusCode::kNotFound ||
      status.code() == absl::StatusCode::kFailedPrecondition) {
    return Report(ToGrpcStatus(status), c);
  }
  std::cerr << "radflux: " << status.message() << "\n";
  return 1;
}

bool WantsGeometry(const OutputFlags& f) {
  return !f.out.empty() || !f.render.empty() || !f.patch_values.empty();
}

// What the flags of `radflux result` and `radflux watch` ask for.
struct OutputArgs {
  OutputFlags output;
  int threads = 0;
};

// Writes snapshot B of `snapshot` as DIR/snapshot_<iteration>.png with the camera flags.
absl::Status WriteSnapshotPng(const v1::Snapshot& snapshot, const JobGeometry& geometry,
                              const std::string& dir, const OutputArgs& args) {
  absl::StatusOr<std::vector<float>> values = SnapshotValues(snapshot);
  if (!values.ok()) return values.status();
  if (snapshot.patch_count() != geometry.mesh.size() || snapshot.bands_size() != kBands) {
    return absl::DataLossError(absl::StrCat("snapshot of ", snapshot.patch_count(), " patches and ",
                                            snapshot.bands_size(), " bands for a mesh of ",
                                            geometry.mesh.size()));
  }
  std::vector<Rgb> radiosity(geometry.mesh.size());
  for (size_t p = 0; p < radiosity.size(); ++p)
    for (int b = 0; b < kBands; ++b) radiosity[p][b] = (*values)[p * kBands + b];
  OutputFlags flags = args.output;
  flags.out.clear();
  flags.patch_values.clear();
  char name[64];
  std::snprintf(name, sizeof(name), "snapshot_%06d.png", snapshot.iteration());
  flags.render = (fs::path(dir) / name).string();
  return WriteOutputs(flags, geometry.scene, geometry.mesh, radiosity, args.threads);
}

// One progress line of a job event on stderr.
void PrintEvent(const v1::JobEvent& event) {
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
  if (!event.message().empty()) std::cerr << ": " << event.message();
  std::cerr << "\n";
}

bool Terminal(v1::JobState state) {
  return state == v1::JOB_STATE_SUCCEEDED || state == v1::JOB_STATE_FAILED ||
         state == v1::JOB_STATE_CANCELLED;
}

// True when a watch stream that failed with `code` before its job's final event may be
// reopened: the server went away (restart, network) rather than refused the watch.
bool StreamMayResume(grpc::StatusCode code) {
  return code == grpc::StatusCode::UNAVAILABLE || code == grpc::StatusCode::CANCELLED ||
         code == grpc::StatusCode::UNKNOWN || code == grpc::StatusCode::INTERNAL ||
         code == grpc::StatusCode::DEADLINE_EXCEEDED;
}

// What a watch of `job_id` has seen so far, across reconnections.
struct WatchProgress {
  uint64_t last_sequence = 0;  // of the last event (not snapshot) received
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  std::string message;
  int64_t snapshots = 0;
};

// One WatchJob stream from after progress->last_sequence until the job's final event (the
// stream is then cancelled: the result can be asked for at once, without waiting for the
// stream's end) or until the stream ends; returns its status.
grpc::Status WatchStream(Client& client, v1::WatchJobRequest request,
                         const std::string& snapshots_dir, const JobGeometry* geometry,
                         const OutputArgs& args, WatchProgress* progress) {
  request.set_after_sequence(progress->last_sequence);
  auto context = client.Context();
  auto reader = client.stub().WatchJob(context.get(), request);
  v1::JobEvent event;
  while (reader->Read(&event)) {
    if (event.has_snapshot()) {
      ++progress->snapshots;
      if (snapshots_dir.empty()) continue;
      if (absl::Status s = WriteSnapshotPng(event.snapshot(), *geometry, snapshots_dir, args);
          !s.ok()) {
        std::cerr << "radflux: snapshot " << event.snapshot().iteration() << ": " << s.message()
                  << "\n";
      }
      continue;
    }
    progress->last_sequence = event.sequence();
    progress->state = event.state();
    progress->message = event.message();
    PrintEvent(event);
    if (Terminal(event.state())) {
      context->TryCancel();
      break;
    }
  }
  return reader->Finish();
}

// Streams a job's events to stderr until it ends, writing each snapshot as a PNG into
// snapshots_dir (if set; then `geometry` is the job's); snapshots are asked every
// `snapshot_every` iterations (without a directory they are only counted). When the stream
// drops after its first event (a server restart), it is reopened after the last event seen,
// for up to `reconnect_seconds` of waiting each time. Returns 0 when the job SUCCEEDED.
int WatchJob(Client& client, const std::string& job_id, const std::string& snapshots_dir,
             const JobGeometry* geometry, const OutputArgs& args, int snapshot_every,
             int reconnect_seconds) {
  v1::WatchJobRequest request;
  request.set_job_id(job_id);
  request.set_snapshot_every(snapshot_every);
  // Snapshots become 8-bit PNGs here: float16 B (11 significant bits) renders the same
  // picture at half the bytes of float32.
  request.set_snapshot_format(v1::SNAPSHOT_FORMAT_FLOAT16);
  if (!snapshots_dir.empty()) {
    request.set_snapshot_every(std::max(1, snapshot_every));
    std::error_code error;
    fs::create_directories(snapshots_dir, error);
  }
  WatchProgress progress;
  for (;;) {
    const grpc::Status status =
        WatchStream(client, request, snapshots_dir, geometry, args, &progress);
    if (Terminal(progress.state)) break;
    if (progress.last_sequence == 0 || reconnect_seconds <= 0 ||
        !StreamMayResume(status.error_code())) {
      if (!status.ok()) return Report(status, client.flags());
      break;
    }
    std::cerr << "radflux: watch of " << job_id << " dropped after event " << progress.last_sequence
              << " (" << status.error_message() << "); reconnecting\n";
    if (!client.WaitForConnected(std::chrono::system_clock::now() +
                                 std::chrono::seconds(reconnect_seconds))) {
      return Report(grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                 absl::StrCat("no answer for ", reconnect_seconds, " s")),
                    client.flags());
    }
  }
  if (request.snapshot_every() > 0) std::cerr << progress.snapshots << " snapshots received\n";
  if (progress.state != v1::JOB_STATE_SUCCEEDED) {
    std::cerr << "radflux: job " << job_id << " ended " << v1::JobState_Name(progress.state)
              << (progress.message.empty() ? "" : ": " + progress.message) << "\n";
    return 1;
  }
  return 0;
}

// A finished job's result as streamed: the mesh the server solved on, B, the report.
struct StreamedResult {
  v1::Job job;
  std::vector<Vec3> positions;
  std::vector<uint32_t> vertices, faces;
  std::vector<Rgb> radiosity;
  std::string report;
};

absl::StatusOr<StreamedResult> FetchResult(Client& client, const std::string& job_id) {
  v1::GetResultRequest request;
  request.set_job_id(job_id);
  auto context = client.Context();
  auto reader = client.stub().GetResult(context.get(), request);
  v1::ResultChunk chunk;
  StreamedResult r;
  uint64_t vertex_count = 0, patch_count = 0;
  std::vector<double> xyz, b;
  while (reader->Read(&chunk)) {
    if (chunk.has_header()) {
      r.job = chunk.header().job();
      vertex_count = chunk.header().vertex_count();
      patch_count = chunk.header().patch_count();
    }
    if (chunk.has_vertices())
      xyz.insert(xyz.end(), chunk.vertices().xyz().begin(), chunk.vertices().xyz().end());
    if (chunk.has_patches()) {
      const v1::PatchChunk& p = chunk.patches();
      r.vertices.insert(r.vertices.end(), p.vertices().begin(), p.vertices().end());
      r.faces.insert(r.faces.end(), p.source_face().begin(), p.source_face().end());
      b.insert(b.end(), p.radiosity().begin(), p.radiosity().end());
    }
    if (chunk.part_case() == v1::ResultChunk::kReportJson) r.report = chunk.report_json();
  }
  if (absl::Status s = FromGrpcStatus(reader->Finish()); !s.ok()) return s;
  if (xyz.size() != 3 * vertex_count || r.faces.size() != patch_count ||
      r.vertices.size() != 4 * patch_count || b.size() != kBands * patch_count) {
    return absl::DataLossError("result stream does not match its header's counts");
  }
  for (size_t i = 0; i < vertex_count; ++i)
    r.positions.push_back({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
  r.radiosity.resize(patch_count);
  for (size_t p = 0; p < patch_count; ++p)
    for (int k = 0; k < kBands; ++k) r.radiosity[p][k] = b[kBands * p + k];
  return r;
}

// True when `mesh` is exactly the mesh the server streamed.
bool SameMesh(const PatchMesh& mesh, const StreamedResult& r) {
  if (mesh.positions.size() != r.positions.size() || mesh.size() != r.faces.size()) return false;
  for (size_t i = 0; i < r.positions.size(); ++i) {
    const Vec3& a = mesh.positions[i];
    const Vec3& b = r.positions[i];
    if (a.x != b.x || a.y != b.y || a.z != b.z) return false;
  }
  for (size_t p = 0; p < mesh.size(); ++p) {
    if (mesh.patches[p].face != r.faces[p]) return false;
    for (int k = 0; k < 4; ++k)
      if (mesh.patches[p].v[k] != r.vertices[4 * p + k]) return false;
  }
  return true;
}

// `radflux result`: the outputs of `radflux solve` from a finished job. `prefetched` is the
// job's geometry when the caller already has it (else it is fetched when needed).
int GetResult(Client& client, const std::string& job_id, const OutputArgs& args,
              const JobGeometry* prefetched = nullptr) {
  if (absl::Status s = ValidateOutputFlags(args.output); !s.ok()) return Fail(s, client.flags());
  absl::StatusOr<StreamedResult> result = FetchResult(client, job_id);
  if (!result.ok()) return Fail(result.status(), client.flags());
  if (WantsGeometry(args.output)) {
    std::optional<JobGeometry> fetched;
    if (!prefetched) {
      absl::StatusOr<JobGeometry> g = FetchGeometry(client, result->job);
      if (!g.ok()) return Fail(g.status(), client.flags());
      fetched = *std::move(g);
    }
    const JobGeometry* geometry = prefetched ? prefetched : &*fetched;
    if (!SameMesh(geometry->mesh, *result)) {
      return Fail(absl::DataLossError("the scene re-meshed here differs from the server's mesh "
                                      "(client and server of different radflux versions?)"),
                  client.flags());
    }
    if (absl::Status s = WriteOutputs(args.output, geometry->scene, geometry->mesh,
                                      result->radiosity, args.threads);
        !s.ok()) {
      return Fail(s, client.flags());
    }
  }
  if (!args.output.report.empty()) {
    std::ofstream out(args.output.report);
    out << result->report << "\n";
    out.close();
    if (!out)
      return Fail(absl::InternalError("cannot write " + args.output.report), client.flags());
  }
  std::cout << result->faces.size() << " patches\n";
  return 0;
}

// `radflux watch` and `radflux submit --watch`: follows the job (snapshots as PNGs into
// snapshots_dir, if set) and, when it succeeds, writes the outputs `args` asks for exactly as
// `radflux result` does. The geometry that snapshots and outputs need is fetched and
// meshed before watching, while the server still runs the job.
int WatchAndWriteResult(Client& client, const std::string& job_id, const std::string& snapshots_dir,
                        const OutputArgs& args, int snapshot_every, int reconnect_seconds) {
  const bool wants_result = WantsGeometry(args.output) || !args.output.report.empty();
  std::optional<JobGeometry> geometry;
  if (!snapshots_dir.empty() || WantsGeometry(args.output)) {
    v1::Job job;
    if (absl::Status s = FetchJob(client, job_id, &job); !s.ok()) return Fail(s, client.flags());
    absl::StatusOr<JobGeometry> fetched = FetchGeometry(client, job);
    if (!fetched.ok()) return Fail(fetched.status(), client.flags());
    geometry = *std::move(fetched);
  }
  const JobGeometry* g = geometry ? &*geometry : nullptr;
  const int watched =
      WatchJob(client, job_id, snapshots_dir, g, args, snapshot_every, reconnect_seconds);
  if (watched != 0 || !wants_result) return watched;
  return GetResult(client, job_id, args, g);
}

// How long a watch whose stream dropped waits for the server to answer again, by default.
constexpr int kReconnectSeconds = 60;

// Adds --reconnect-seconds to a command that watches a job.
void AddReconnectFlag(CLI::App& command, int& seconds) {
  command
      .add_option("--reconnect-seconds", seconds,
                  "when the watch stream drops (server restart), reconnect and resume after "
                  "the last event seen, waiting up to this long each time (0 = give up)")
      ->check(CLI::NonNegativeNumber);
}

// Adds the connection flags to `command` (and to the top level once), bound to `c`.
void AddConnectionFlags(CLI::App& command, ConnectionFlags& c) {
  command.add_option("--server", c.server, "radfluxd address HOST:PORT");
  command.add_option("--token", c.token, "bearer token");
  command.add_option("--tls-ca", c.tls_ca, "PEM CA certificate: connect with TLS");
  auto* cert = command.add_option("--tls-cert", c.tls_cert,
                                  "PEM client certificate (for a radfluxd with --tls-client-ca)");
  auto* key = command.add_option("--tls-key", c.tls_key, "PEM private key of --tls-cert");
  cert->needs(key);
  key->needs(cert);
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
  auto submit_outputs = std::make_shared<OutputFlags>();
  submit->add_flag("--watch", *watch,
                   "watch the job until it ends; then write the output options' files, as "
                   "`radflux result` does");
  submit->add_option("--request-id", *request_id, "idempotency key: a retry returns the same job");
  auto reconnect_seconds = std::make_shared<int>(kReconnectSeconds);
  AddReconnectFlag(*submit, *reconnect_seconds);
  AddOutputFlags(*submit, *submit_outputs);
  AddConnectionFlags(*submit, *c);
  submit->callback([=, &exit_code] {
    if (const std::vector<std::string> given = GivenOutputFlags(*submit);
        !given.empty() && !*watch) {
      return void(exit_code = ReportStatus(
                      "submit", absl::InvalidArgumentError(absl::StrCat(
                                    given.front(),
                                    " needs --watch: outputs are written when the watched job "
                                    "succeeds (without --watch, run `radflux result JOB ",
                                    given.front(), " ...` once it has)"))));
    }
    if (absl::Status s = ValidateOutputFlags(*submit_outputs); !s.ok()) {
      return void(exit_code = Fail(s, *c));
    }
    absl::StatusOr<JobOptions> options = ToJobOptions(*job_flags);
    if (options.ok() && (options->hierarchical.enabled || options->adaptive.passes > 0)) {
      options = absl::InvalidArgumentError(
          "--solver hierarchical and --adaptive-passes run in `radflux solve` only; the "
          "service (radflux.v1.SolveOptions) does not carry them yet");
    }
    if (!options.ok()) {
      std::cerr << "radflux: " << options.status().message() << "\n";
      exit_code = 1;
      return;
    }
    absl::StatusOr<SceneFile> scene_file = ReadSceneFile(*scene);
    if (!scene_file.ok()) return void(exit_code = Fail(scene_file.status(), *c));
    Client client(*c);
    v1::SubmitJobRequest request;
    *request.mutable_options() = ToProto(*options);
    request.set_request_id(*request_id);
    v1::Job job;
    const grpc::Status status = SubmitScene(client, *scene_file, request, &job);
    if (!status.ok()) return void(exit_code = Report(status, *c));
    std::cerr << "submitted " << job.job_id() << " (scene " << request.scene_sha256().substr(0, 12)
              << ")\n";
    if (*watch) {
      const OutputArgs outputs{*submit_outputs, job_flags->threads};  // render as `solve` does
      exit_code = WatchAndWriteResult(client, job.job_id(), "", outputs, 0, *reconnect_seconds);
    }
    std::cout << job.job_id() << std::endl;
  });

  auto* watch_cmd = app.add_subcommand("watch", "follow a job's progress");
  auto job_id = std::make_shared<std::string>();
  auto snapshots = std::make_shared<std::string>();
  auto watch_args = std::make_shared<OutputArgs>();
  auto snapshot_every = std::make_shared<int>(0);
  watch_cmd->add_option("job", *job_id, "job id")->required();
  watch_cmd->add_option("--snapshots", *snapshots,
                        "write each snapshot as a rendered PNG into DIR (camera flags apply)");
  watch_cmd
      ->add_option("--snapshot-every", *snapshot_every,
                   "ask for a snapshot every N solver iterations (default with --snapshots: "
                   "1; without it they are received and counted only)")
      ->check(CLI::NonNegativeNumber);
  AddOutputFlags(*watch_cmd, watch_args->output);
  watch_cmd->add_option("--threads", watch_args->threads, "render threads (0 = all cores)");
  AddReconnectFlag(*watch_cmd, *reconnect_seconds);
  AddConnectionFlags(*watch_cmd, *c);
  watch_cmd->callback([=, &exit_code] {
    if (absl::Status s = ValidateOutputFlags(watch_args->output); !s.ok()) {
      return void(exit_code = Fail(s, *c));
    }
    Client client(*c);
    exit_code = WatchAndWriteResult(client, *job_id, *snapshots, *watch_args, *snapshot_every,
                                    *reconnect_seconds);
  });

  auto* result =
      app.add_subcommand("result", "fetch a finished job's result: the outputs of `radflux solve`");
  auto result_id = std::make_shared<std::string>();
  auto result_args = std::make_shared<OutputArgs>();
  result->add_option("job", *result_id, "job id")->required();
  AddOutputFlags(*result, result_args->output);
  result->add_option("--threads", result_args->threads, "render threads (0 = all cores)");
  AddConnectionFlags(*result, *c);
  result->callback([=, &exit_code] {
    Client client(*c);
    exit_code = GetResult(client, *result_id, *result_args);
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
