#include "client/service_commands.h"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "absl/strings/str_cat.h"
#include "client/exit_status.h"
#include "client/job_flags.h"
#include "client/import_flags.h"
#include "client/job_watch.h"
#include "client/output_flags.h"
#include "client/scene_upload.h"
#include "client/service_client.h"
#include "client/view/view_command.h"
#include "client/viewfactors_flags.h"
#include "radflux/v1/radiosity.grpc.pb.h"
#include "solver/formfactor/view_factor_flags.h"
#include "solver/mesh/subdivide.h"
#include "solver/scene/validation.h"
#include "wire/grpc_credentials.h"
#include "wire/proto_convert.h"
#include "wire/scene_stream.h"
#include "wire/view_factor_convert.h"
#include "wire/stored_scene.h"

namespace radflux::cli {
namespace {

bool WantsGeometry(const OutputFlags& f) {
  return !f.out.empty() || !f.render.empty() || !f.patch_values.empty();
}

// Writes `bytes` to `path` ("" = nothing to write); INTERNAL naming the file on failure.
absl::Status WriteFile(const std::string& path, const std::string& bytes) {
  if (path.empty()) return absl::OkStatus();
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  out.close();
  if (!out) return absl::InternalError("cannot write " + path);
  return absl::OkStatus();
}

// The files of a view-factor job's result: what `radflux viewfactors` writes to -o and --svf.
struct ViewFactorFiles {
  std::string output, svf, report;  // "" = not asked for
};

// `radflux result` of a view-factor job (`submit --viewfactors`): its files, the bytes
// `radflux viewfactors` writes for the same model and options; then, as GetResult, the
// job's verdict (rows summing above 1: kExitRowSumOver, with one line unless the caller said
// it already).
int GetViewFactorResult(Client& client, const std::string& job_id, const ViewFactorFiles& files,
                        bool say_shortfall = true) {
  absl::StatusOr<StreamedResult> result =
      FetchResult(client, job_id, /*report_only=*/files.output.empty() && files.svf.empty());
  if (!result.ok()) return Fail(result.status(), client.flags());
  if (!result->job.options().has_viewfactors()) {
    return Fail(absl::InvalidArgumentError(
                    job_id + " is not a view-factor job: -o and --svf are for jobs of `radflux "
                             "submit --viewfactors` (a radiosity job's mesh is --out)"),
                client.flags());
  }
  result->report += "\n";
  for (const auto& [path, bytes] : {std::pair{files.output, &result->view_factors},
                                    std::pair{files.svf, &result->sky_view_factors},
                                    std::pair{files.report, &result->report}}) {
    if (absl::Status s = WriteFile(path, *bytes); !s.ok()) return Fail(s, client.flags());
  }
  std::cout << result->job.patches() << " surfaces\n";
  const int verdict = SucceededJobExitCode(result->job);
  if (verdict != 0 && say_shortfall)
    return ReportJobShortfall("result", job_id, result->job.message(), verdict);
  return verdict;
}

// `radflux result`: the outputs of `radflux solve` from a finished job. `prefetched` is the
// job's geometry when the caller already has it (else it is fetched when needed). A job whose
// solve stopped short of its tolerance or whose energy balance is off gets its outputs too,
// then kExitNotConverged or kExitEnergyImbalance (with one line saying so unless
// `say_shortfall` is false: the caller said it already).
int GetResult(Client& client, const std::string& job_id, const OutputArgs& args,
              const JobGeometry* prefetched = nullptr, bool say_shortfall = true) {
  if (absl::Status s = ValidateOutputFlags(args.output); !s.ok()) return Fail(s, client.flags());
  // The mesh and B are streamed only for the outputs that need them (most of the bytes).
  absl::StatusOr<StreamedResult> result =
      FetchResult(client, job_id, /*report_only=*/!WantsGeometry(args.output));
  if (!result.ok()) return Fail(result.status(), client.flags());
  if (result->job.options().has_viewfactors() && WantsGeometry(args.output)) {
    return Fail(absl::InvalidArgumentError(
                    job_id + " is a view-factor job: fetch its files with -o FILE [--svf FILE]"),
                client.flags());
  }
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
                                      result->radiosity, result->indirect,
                                      geometry->seed, args.threads);
        !s.ok()) {
      return Fail(s, client.flags());
    }
  }
  if (absl::Status s = WriteFile(args.output.report, result->report + "\n"); !s.ok()) {
    return Fail(s, client.flags());
  }
  if (result->job.options().has_viewfactors()) {
    std::cout << result->job.patches() << " surfaces (a view-factor job: -o FILE writes them)\n";
  } else {
    std::cout << result->patch_count << " patches\n";
  }
  const int verdict = SucceededJobExitCode(result->job);
  if (verdict != 0 && say_shortfall)
    return ReportJobShortfall("result", job_id, result->job.message(), verdict);
  return verdict;
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
  const bool succeeded = watched == 0 || watched == kExitNotConverged ||
                         watched == kExitEnergyImbalance;
  if (!succeeded || !wants_result) return watched;
  return GetResult(client, job_id, args, g, /*say_shortfall=*/watched == 0);
}

// The request of `radflux submit MODEL --viewfactors`: the options given, checked here as
// `radflux viewfactors` checks them where the model is not needed (the server checks the
// rest: it reads the model).
absl::StatusOr<v1::SolveOptions> ViewFactorRequest(const std::vector<std::string>& given,
                                                  const std::string& model, const JobFlags& job,
                                                  const ImportFlags& import_flags,
                                                  const ViewFactorFlags& vf) {
  const ViewFactorIntegration requested = RequestedIntegration(vf);
  if (absl::Status s = CheckViewFactorFlags(given, model, requested, requested); !s.ok()) return s;
  absl::StatusOr<JobOptions> options = ToJobOptions(job);
  if (!options.ok()) return options.status();
  absl::StatusOr<ImportOptions> import = ToImportOptions(import_flags);
  if (!import.ok()) return import.status();
  v1::SolveOptions full = ToProto(*options);
  *full.mutable_import_options() = ToProto(*import);
  v1::ViewFactorOptions p;
  p.set_by(vf.by);
  p.set_format(vf.format);
  p.set_min_vf(vf.min_vf);
  p.set_integration(vf.integration);
  p.set_vf_tolerance(vf.pairs.tolerance);
  p.set_far_ratio(vf.pairs.far_ratio);
  p.set_middle_ratio(vf.pairs.middle_ratio);
  p.set_memory_limit(vf.memory_limit);
  return ViewFactorRequestOptions(std::move(full), p, given);
}

// INVALID_ARGUMENT when the command line mixes the kinds of job: a view-factor flag without
// --viewfactors, or a radiosity output flag with it; or asks for files without --watch.
absl::Status CheckSubmitKind(const CLI::App& submit, bool viewfactors, bool watch) {
  std::vector<std::string> vf_given;
  for (const CLI::Option* option : submit.get_options()) {
    if (option->get_group() == kViewFactorGroup && option->count() > 0) {
      vf_given.push_back(option->get_name());
    }
  }
  const std::vector<std::string> outputs = GivenOutputFlags(submit);
  if (!viewfactors && !vf_given.empty()) {
    return absl::InvalidArgumentError(vf_given.front() + " needs --viewfactors");
  }
  if (viewfactors && !outputs.empty()) {
    return absl::InvalidArgumentError(outputs.front() +
                                      " is for radiosity jobs; a view-factor job writes -o and --svf");
  }
  const std::vector<std::string>& files = viewfactors ? vf_given : outputs;
  for (const std::string& flag : files) {
    if (flag != "-o" && flag != "--output" && flag != "--svf" && viewfactors) continue;
    if (watch) break;
    return absl::InvalidArgumentError(absl::StrCat(
        flag, " needs --watch: outputs are written when the watched job succeeds (without "
              "--watch, run `radflux result JOB ", flag, " ...` once it has)"));
  }
  return absl::OkStatus();
}

// The verb's connection, for the rest of the process: never destroyed, because destroying
// the last gRPC channel shuts gRPC down (its threads joined, with sleeps), which radflux-service
// skips by ending with _Exit once its output is written (service_main.cc): ~3-6 ms of a round
// trip.
Client& ProcessClient(const ConnectionFlags& c) { return *new Client(c); }

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

// `radflux submit MODEL --viewfactors ...`: uploads the model, submits the view-factor job
// and prints its id; with --watch follows it and writes its files as `radflux result` does.
int SubmitViewFactors(const ConnectionFlags& c, const std::string& model,
                      const std::vector<std::string>& given, const JobFlags& job,
                      const ImportFlags& import, const ViewFactorFlags& vf,
                      const std::string& request_id, bool watch, int reconnect_seconds) {
  absl::StatusOr<v1::SolveOptions> options = ViewFactorRequest(given, model, job, import, vf);
  if (!options.ok()) return ReportStatus("submit", options.status());
  absl::StatusOr<SceneFile> scene_file = ReadSceneFile(model);
  if (!scene_file.ok()) return Fail(scene_file.status(), c);
  Client& client = ProcessClient(c);
  v1::SubmitJobRequest request;
  *request.mutable_options() = *std::move(options);
  request.set_request_id(request_id);
  v1::Job submitted;
  const grpc::Status status = SubmitScene(client, *scene_file, request, &submitted);
  if (!status.ok()) return Report(status, c);
  std::cerr << "submitted " << submitted.job_id() << " (scene "
            << request.scene_sha256().substr(0, 12) << ")\n";
  int exit_code = 0;
  if (watch) {
    const int watched = WatchJob(client, submitted.job_id(), "", nullptr, OutputArgs{}, 0,
                                 reconnect_seconds);
    const bool succeeded = watched == 0 || watched == kExitRowSumOver;
    exit_code = !succeeded ? watched
                           : GetViewFactorResult(client, submitted.job_id(),
                                                 ViewFactorFiles{vf.output, vf.svf, ""},
                                                 /*say_shortfall=*/watched == 0);
  }
  std::cout << submitted.job_id() << std::endl;
  return exit_code;
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
  submit
      ->add_option("scene", *scene,
                   "scene file (.obj, .gltf, .glb, .mgf, .stl, .vs3); the files it names (MTL, "
                   "textures, buffers, includes) are sent with it")
      ->required();
  AddJobFlags(*submit, *job_flags);
  auto import_flags = std::make_shared<ImportFlags>();
  AddImportFlags(*submit, *import_flags);
  auto submit_outputs = std::make_shared<OutputFlags>();
  submit->add_flag("--watch", *watch,
                   "watch the job until it ends; then write the output options' files, as "
                   "`radflux result` does");
  submit->add_option("--request-id", *request_id, "idempotency key: a retry returns the same job");
  auto reconnect_seconds = std::make_shared<int>(kReconnectSeconds);
  AddReconnectFlag(*submit, *reconnect_seconds);
  AddOutputFlags(*submit, *submit_outputs);
  auto viewfactors = std::make_shared<bool>(false);
  auto vf_flags = std::make_shared<ViewFactorFlags>();
  submit->add_flag("--viewfactors", *viewfactors,
                   "a view-factor job (the options of `radflux viewfactors`; its files are "
                   "written by --watch -o FILE [--svf FILE] or `radflux result JOB -o FILE`)");
  AddViewFactorFlags(*submit, *vf_flags, /*output_required=*/false);
  AddConnectionFlags(*submit, *c);
  submit->callback([=, &exit_code] {
    if (absl::Status s = CheckSubmitKind(*submit, *viewfactors, *watch); !s.ok()) {
      return void(exit_code = ReportStatus("submit", s));
    }
    if (*viewfactors) {
      return void(exit_code = SubmitViewFactors(*c, *scene, GivenFlagNames(*submit), *job_flags,
                                                *import_flags, *vf_flags, *request_id, *watch,
                                                *reconnect_seconds));
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
    absl::StatusOr<ImportOptions> import = ToImportOptions(*import_flags);
    if (!import.ok()) return void(exit_code = Fail(import.status(), *c));
    absl::StatusOr<SceneFile> scene_file = ReadSceneFile(*scene);
    if (!scene_file.ok()) return void(exit_code = Fail(scene_file.status(), *c));
    Client& client = ProcessClient(*c);
    v1::SubmitJobRequest request;
    *request.mutable_options() = ToProto(*options);
    *request.mutable_options()->mutable_import_options() = ToProto(*import);
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
    Client& client = ProcessClient(*c);
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
  auto vf_files = std::make_shared<ViewFactorFiles>();
  result->add_option("-o,--output", vf_files->output,
                     "a view-factor job's file (its --format), as `radflux viewfactors -o` "
                     "writes it");
  result->add_option("--svf", vf_files->svf,
                     "a view-factor job's sky view factors, as `radflux viewfactors --svf` "
                     "writes them");
  AddConnectionFlags(*result, *c);
  result->callback([=, &exit_code] {
    Client& client = ProcessClient(*c);
    if (vf_files->output.empty() && vf_files->svf.empty()) {
      return void(exit_code = GetResult(client, *result_id, *result_args));
    }
    if (const std::vector<std::string> given = GivenOutputFlags(*result);
        std::find_if(given.begin(), given.end(),
                     [](const std::string& flag) { return flag != "--report"; }) != given.end()) {
      return void(exit_code = ReportStatus(
                      "result", absl::InvalidArgumentError(
                                    "-o and --svf (a view-factor job's files) go without the "
                                    "radiosity outputs (--out, --render, --patch-values)")));
    }
    exit_code = GetViewFactorResult(
        client, *result_id, ViewFactorFiles{vf_files->output, vf_files->svf, result_args->output.report});
  });

  auto* cancel = app.add_subcommand("cancel", "cancel a queued or running job");
  auto cancel_id = std::make_shared<std::string>();
  cancel->add_option("job", *cancel_id, "job id")->required();
  AddConnectionFlags(*cancel, *c);
  cancel->callback([=, &exit_code] {
    Client& client = ProcessClient(*c);
    v1::CancelJobRequest request;
    request.set_job_id(*cancel_id);
    v1::Job job;
    const grpc::Status status = client.stub().CancelJob(client.Context().get(), request, &job);
    if (!status.ok()) return void(exit_code = Report(status, *c));
    std::cout << job.job_id() << " " << v1::JobState_Name(job.state()) << "\n";
  });

  auto* view = app.add_subcommand(
      "view", "a live 3D view in the browser of a job (JOB), a saved result (RESULT.glb) or "
              "the server's jobs (no argument), served on 127.0.0.1");
  auto view_args = std::make_shared<ViewArgs>();
  view->add_option("target", view_args->target, "job id or .glb file (default: the job list)");
  view->add_option("--port", view_args->port, "port on 127.0.0.1 (default: a free one)")
      ->check(CLI::Range(0, 65535));
  AddReconnectFlag(*view, view_args->reconnect_seconds);
  AddConnectionFlags(*view, *c);
  view->callback([=, &exit_code] { exit_code = RunView(*c, *view_args); });

  auto* list = app.add_subcommand(
      "list", "list jobs, newest first: id, state, phase, patches, message, owner");
  auto page_size = std::make_shared<int>(100);
  list->add_option("--limit", *page_size, "at most this many jobs");
  AddConnectionFlags(*list, *c);
  list->callback([=, &exit_code] {
    Client& client = ProcessClient(*c);
    v1::ListJobsRequest request;
    request.set_page_size(*page_size);
    v1::ListJobsResponse response;
    const grpc::Status status = client.stub().ListJobs(client.Context().get(), request, &response);
    if (!status.ok()) return void(exit_code = Report(status, *c));
    for (const v1::Job& job : response.jobs()) {
      const int verdict = SucceededJobExitCode(job);
      std::cout << job.job_id() << "  " << v1::JobState_Name(job.state())
                << (verdict == kExitNotConverged      ? " NOT_CONVERGED"
                    : verdict == kExitEnergyImbalance ? " ENERGY_BALANCE_OFF"
                                                      : "")
                << "  "
                << v1::Phase_Name(job.phase()) << "  patches " << job.patches() << "  "
                << job.message() << "  owner " << job.owner() << "\n";
    }
  });
}

}  // namespace radflux::cli
