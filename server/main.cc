// radfluxd: the radflux gRPC server.
//   radfluxd --listen HOST:PORT --data-dir DIR [--jobs N] [--threads N] [--token T]
//            [--tokens-file F] [--principal-running-jobs N] [--principal-patches N]
//            [--principal-cpu-seconds S]
//            [--tls-cert F --tls-key F [--tls-client-ca F]] [--max-patches N]
//            [--max-memory BYTES] [--worker-token T | --allow-workers-without-token]
//            [--lease-seconds S] [--verify-fraction F] [--max-concurrent-uploads N]
//   radfluxd --worker --server HOST:PORT [--threads N] [--worker-token T] [--tls-ca F]
//            [--tls-cert F --tls-key F]
//   (a worker node: builds row blocks for the server, see server/worker_node.h)
// Prints "radfluxd listening on HOST:PORT" (the port actually bound, so :0 works) once
// serving. SIGTERM/SIGINT: running jobs checkpoint, then the server exits 0.
#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>
#include <signal.h>
#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <iostream>
#include <thread>

#include "server/api/principals.h"
#include "server/api/radiosity_service.h"
#include "server/api/tokens_file.h"
#include "server/jobs/job_manager.h"
#include "server/jobs/work_queue.h"
#include "server/store/job_store.h"
#include "server/workers/row_farm.h"
#include "server/workers/worker_node.h"
#include "server/workers/worker_service.h"
#include "wire/grpc_credentials.h"

namespace {

constexpr int kMaxMessageBytes = 8 << 20;
constexpr int kWorkThreads = 4;

// The signals that stop radfluxd: blocked in every thread, waited for by one.
sigset_t ShutdownSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  return set;
}

// Blocks until SIGTERM or SIGINT arrives; returns which.
int WaitForShutdownSignal() {
  const sigset_t set = ShutdownSignals();
  int signal = 0;
  sigwait(&set, &signal);
  return signal;
}

struct Flags {
  std::string listen;
  std::string data_dir;
  int jobs = 1;
  int threads = 0;
  std::string token;
  std::string tokens_file;             // principals (server/api/tokens_file.h)
  radflux::PrincipalLimits principal;  // the limits of a principal that sets none
  std::string tls_cert, tls_key;
  std::string tls_client_ca;  // mutual TLS: clients must present a certificate of this CA
  radflux::ManagerOptions manager;
  // Worker nodes: the server's side, and the worker role.
  std::string worker_token;
  double lease_seconds = 300;
  double verify_fraction = radflux::kDefaultVerifyFraction;
  bool allow_workers_without_token = false;
  bool worker = false;
  radflux::WorkerNodeOptions node;
};

// The principals of --token and --tokens-file, or an error line; the worker token must be
// none of their tokens (a client could otherwise serve as a worker, or a worker as a client).
absl::StatusOr<radflux::Principals> LoadPrincipals(const Flags& flags) {
  std::vector<radflux::TokenEntry> entries;
  if (!flags.tokens_file.empty()) {
    absl::StatusOr<std::vector<radflux::TokenEntry>> read =
        radflux::ReadTokensFile(flags.tokens_file, flags.principal);
    if (!read.ok()) return read.status();
    entries = *std::move(read);
  }
  absl::StatusOr<radflux::Principals> principals =
      radflux::Principals::Make(flags.token, std::move(entries), flags.principal);
  if (principals.ok() && !flags.worker_token.empty() &&
      principals->IsClientToken(flags.worker_token)) {
    return absl::InvalidArgumentError(
        "--worker-token must differ from every client token (--token, --tokens-file)");
  }
  return principals;
}

int Serve(const Flags& flags) {
  absl::StatusOr<radflux::Principals> principals = LoadPrincipals(flags);
  if (!principals.ok()) {
    std::cerr << "radfluxd: " << principals.status().message() << "\n";
    return 2;
  }
  absl::StatusOr<std::unique_ptr<radflux::JobStore>> store =
      radflux::JobStore::Open(flags.data_dir);
  if (!store.ok()) {
    spdlog::error("{}", std::string(store.status().message()));
    return 1;
  }
  radflux::RowFarm farm(flags.lease_seconds, flags.verify_fraction);
  radflux::ManagerOptions manager_options = flags.manager;
  manager_options.farm = &farm;
  manager_options.limits_of = [&](const std::string& owner) { return principals->LimitsOf(owner); };
  radflux::JobManager manager(**store, manager_options);
  radflux::WorkQueue work(kWorkThreads);
  radflux::RadiosityService service(manager, work, *principals);
  radflux::WorkerService worker_service(farm, manager, flags.worker_token,
                                        flags.allow_workers_without_token);
  const std::shared_ptr<grpc::ServerCredentials> credentials =
      radflux::ServerCredentialsFromFiles(flags.tls_cert, flags.tls_key, flags.tls_client_ca);
  if (!credentials) {
    spdlog::error("cannot read --tls-cert {} / --tls-key {} / --tls-client-ca {}", flags.tls_cert,
                  flags.tls_key, flags.tls_client_ca);
    return 1;
  }
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(flags.listen, credentials, &port);
  builder.SetMaxReceiveMessageSize(kMaxMessageBytes);
  builder.SetMaxSendMessageSize(kMaxMessageBytes);
  builder.RegisterService(&service);
  builder.RegisterService(&worker_service);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    spdlog::error("cannot listen on {}", flags.listen);
    return 1;
  }
  if (absl::Status s = manager.Start(); !s.ok()) {
    spdlog::error("cannot start jobs: {}", std::string(s.message()));
    return 1;
  }
  const std::string host = flags.listen.substr(0, flags.listen.rfind(':'));
  std::cout << "radfluxd listening on " << host << ":" << port << std::endl;
  const char* tls = flags.tls_cert.empty()        ? "off"
                    : flags.tls_client_ca.empty() ? "on"
                                                  : "on, client certificates required";
  spdlog::info("radfluxd " RADFLUX_VERSION
               " serving on {}:{} (data {}, {} job(s) at once, tls {}, principals {})",
               host, port, flags.data_dir, flags.manager.jobs, tls,
               principals->open() ? "off (everyone is 'default', an admin)"
                                  : std::to_string(principals->size()));

  std::thread signals([&] {
    const int signal = WaitForShutdownSignal();
    spdlog::info("signal {}: checkpointing running jobs and shutting down", signal);
    server->GetHealthCheckService()->SetServingStatus(false);
    manager.Shutdown();
    farm.Shutdown();
    server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  });
  server->Wait();
  signals.join();
  spdlog::info("radfluxd stopped");
  return 0;
}

// The worker role: runs until SIGTERM/SIGINT (0) or the server refuses it (2).
int Work(const Flags& flags) {
  std::atomic<bool> stop{false};
  std::thread signals([&] {
    const int signal = WaitForShutdownSignal();
    spdlog::info("signal {}: worker stopping", signal);
    stop = true;
  });
  signals.detach();  // exits with the process
  spdlog::info("worker for {} ({} thread(s), tls {}, token {})", flags.node.server,
               flags.node.threads > 0 ? std::to_string(flags.node.threads) : "all",
               flags.node.tls_ca.empty() ? "off" : "on",
               flags.node.worker_token.empty() ? "off" : "on");
  return radflux::RunWorkerNode(flags.node, stop);
}

}  // namespace

int main(int argc, char** argv) {
  // Block the shutdown signals in every thread; one thread waits for them with sigwait.
  const sigset_t set = ShutdownSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  signal(SIGPIPE, SIG_IGN);
  // Logs go to stderr; stdout carries only the "listening on" line scripts read.
  spdlog::set_default_logger(spdlog::stderr_color_mt("radfluxd"));
  spdlog::cfg::load_env_levels();  // SPDLOG_LEVEL=debug: per-step timings of every job

  CLI::App app{"radfluxd: the radflux radiosity solver service"};
  app.set_version_flag("--version", "radfluxd " RADFLUX_VERSION);
  Flags flags;
  app.add_option("--listen", flags.listen,
                 "HOST:PORT to serve on (port 0 = any free port); required unless --worker");
  app.add_option("--data-dir", flags.data_dir,
                 "directory of the job store; required unless --worker");
  app.add_option("--jobs", flags.manager.jobs, "jobs running at once")->check(CLI::Range(1, 256));
  app.add_option("--threads", flags.manager.threads,
                 "OpenMP threads shared by running jobs (0 = all cores)")
      ->check(CLI::Range(0, 4096));
  app.add_option("--token", flags.token,
                 "require a bearer token on every call; this one is the principal 'default', an "
                 "admin (sees every job), which also owns jobs stored before principals existed");
  app.add_option("--tokens-file", flags.tokens_file,
                 "principals: one 'PRINCIPAL TOKEN [admin] [running_jobs=N] [patches=N] "
                 "[cpu_seconds=S]' a line (# comments; TOKEN '-': TLS client certificate only, "
                 "its CN naming the principal); each sees only its own jobs and scenes, an "
                 "admin all");
  app.add_option("--principal-running-jobs", flags.principal.running_jobs,
                 "a principal's jobs queued or running at once, unless its line says "
                 "running_jobs=N (0 = no limit; the default)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--principal-patches", flags.principal.patches,
                 "the patches of one job of a principal, unless its line says patches=N (0 = "
                 "--max-patches alone; the default)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--principal-cpu-seconds", flags.principal.cpu_seconds,
                 "the CPU seconds (threads x running time) one job of a principal may take, "
                 "unless its line says cpu_seconds=S; a job reaching it fails (0 = no limit; "
                 "the default)")
      ->check(CLI::NonNegativeNumber);
  auto* cert = app.add_option("--tls-cert", flags.tls_cert,
                              "PEM server certificate (enables TLS); worker: the client "
                              "certificate it presents to a server with --tls-client-ca");
  auto* key = app.add_option("--tls-key", flags.tls_key, "PEM private key of --tls-cert");
  cert->needs(key);
  key->needs(cert);
  app.add_option("--tls-client-ca", flags.tls_client_ca,
                 "PEM CA certificate: require every client to present a certificate it signed "
                 "(mutual TLS; clients without one get UNAVAILABLE)")
      ->needs(cert);
  app.add_option("--max-patches", flags.manager.max_patches, "refuse jobs with more patches")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-memory", flags.manager.max_memory,
                 "memory per job (estimated at submit; default: half the RAM). A job whose "
                 "rows do not fit runs with BYTES minus the rest of its estimate of rows in "
                 "memory and the others spilled to its job directory (jacobi, gauss_seidel, "
                 "auto; auto becomes gauss_seidel); refused: jobs that do not fit even "
                 "spilled, or do not fit and cannot spill (cg, southwell, direct, "
                 "hierarchical, adaptive)");
  app.add_option("--max-upload", flags.manager.max_upload, "largest scene upload in bytes");
  app.add_option("--max-concurrent-uploads", flags.manager.max_concurrent_uploads,
                 "uploads in progress at once (each holds its scene in memory until it is "
                 "stored); more are refused with RESOURCE_EXHAUSTED")
      ->check(CLI::PositiveNumber);
  app.add_option(
         "--checkpoint-seconds", flags.manager.checkpoint_seconds,
         "at most one checkpoint of row blocks and one of the solver state per job per this "
         "many seconds (0 = after every row block / iteration), and a row checkpoint as soon "
         "as 16 MiB of row blocks wait; a kill -9 loses at most this much work")
      ->check(CLI::Range(0.0, 86400.0));
  app.add_option("--solve-delay-ms", flags.manager.solve_delay_ms,
                 "testing: sleep this long after every solver iteration")
      ->check(CLI::Range(0, 60000));
  app.add_option("--testing-submit-delay-ms", flags.manager.submit_delay_ms,
                 "testing: sleep this long in each submit between its disk check and its insert "
                 "(other submits wait: the check and the insert are one step)")
      ->check(CLI::Range(0, 60000));
  app.add_option("--snapshot-interval-ms", flags.manager.snapshot_interval_ms,
                 "watchers get at most one snapshot of a job per this many milliseconds of its "
                 "solve: the newest, and always the last iteration's before the job ends (0 = "
                 "every snapshot a watcher's snapshot_every asks for)")
      ->check(CLI::Range(0, 3600000));
  app.add_option("--worker-token", flags.worker_token,
                 "server: require this bearer token of workers (without it, workers are refused "
                 "unless --allow-workers-without-token); worker: send it");
  app.add_flag("--allow-workers-without-token", flags.allow_workers_without_token,
               "server without --worker-token: accept any worker that reaches the port (their "
               "rows are still verified)");
  app.add_option("--verify-fraction", flags.verify_fraction,
                 "the fraction of each worker row block's rows the server recomputes and "
                 "compares bit for bit (at least one row per block; 0 = none; rows summing "
                 "above their limit, 1 or 0.999 / rho, are always recomputed)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--lease-seconds", flags.lease_seconds,
                 "a row block leased to a worker is leased again after this many seconds")
      ->check(CLI::Range(0.1, 86400.0));
  app.add_flag("--worker", flags.worker, "run as a worker node of --server");
  app.add_option("--server", flags.node.server, "worker: HOST:PORT of the radfluxd to work for");
  app.add_option("--tls-ca", flags.node.tls_ca, "worker: PEM CA certificate: connect with TLS");
  app.add_option("--tls-server-name", flags.node.tls_server_name,
                 "worker: the name to check in the server's certificate (default: from --server)");
  app.add_option("--testing-block-delay-ms", flags.node.block_delay_ms,
                 "testing: sleep this long after building each row block (server and worker)")
      ->check(CLI::Range(0, 600000));
  CLI11_PARSE(app, argc, argv);
  if (flags.worker) {
    if (flags.node.server.empty()) {
      std::cerr << "radfluxd: --worker needs --server HOST:PORT\n";
      return 2;
    }
    flags.node.threads = flags.manager.threads;
    flags.node.worker_token = flags.worker_token;
    flags.node.tls_cert = flags.tls_cert;
    flags.node.tls_key = flags.tls_key;
    return Work(flags);
  }
  if (flags.listen.empty() || flags.data_dir.empty()) {
    std::cerr << "radfluxd: --listen and --data-dir are required (or --worker --server)\n";
    return 2;
  }
  flags.manager.block_delay_ms = flags.node.block_delay_ms;
  return Serve(flags);
}
