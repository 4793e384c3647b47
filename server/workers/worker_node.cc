#include "server/workers/worker_node.h"

#include <grpcpp/grpcpp.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <future>
#include <map>
#include <mutex>
#include <thread>

#include "absl/strings/str_cat.h"
#include "radflux/v1/worker.grpc.pb.h"
#include "server/store/job_store.h"
#include "server/workers/block_wire.h"
#include "server/workers/view_factor_work.h"
#include "solver/core/parallel.h"
#include "solver/pipeline.h"
#include "wire/grpc_credentials.h"
#include "wire/proto_convert.h"
#include "wire/scene_stream.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kMaxMessageBytes = 64 << 20;
constexpr size_t kMaxResultBytes = 7 << 20;  // under the server's 8 MiB receive limit
constexpr size_t kJobsCached = 2;
constexpr std::chrono::milliseconds kPoll{200};
constexpr std::chrono::seconds kHeartbeatInterval{1};  // see Heartbeat in worker.proto

// A job as a worker holds it: prepared like the server prepares it, and its row builder.
struct PreparedWork {
  std::unique_ptr<PreparedJob> job;
  std::unique_ptr<RowBuilder> builder;
  double cutoff = 0;
  std::unique_ptr<ViewFactorWork> view_factors;  // a view-factor job's (then job is null)
};
using WorkOrError = absl::StatusOr<std::shared_ptr<const PreparedWork>>;

void AddAuth(grpc::ClientContext& context, const std::string& token) {
  if (!token.empty()) context.AddMetadata("authorization", "Bearer " + token);
}

// The scene of `sha256` from the server, checked against its address.
absl::StatusOr<StoredScene> FetchScene(v1::Worker::Stub& stub, const std::string& token,
                                       const std::string& sha256) {
  grpc::ClientContext context;
  AddAuth(context, token);
  v1::FetchSceneRequest request;
  request.set_sha256(sha256);
  auto reader = stub.FetchScene(&context, request);
  return ReadSceneChunks(*reader, sha256);
}

// Prepared jobs by job id; each is fetched and prepared once (threads asking meanwhile
// wait for it); the oldest is dropped beyond kJobsCached.
class JobCache {
 public:
  JobCache(v1::Worker::Stub& stub, std::string token) : stub_(stub), token_(std::move(token)) {}

  WorkOrError Get(const v1::BlockLease& lease) {
    std::promise<WorkOrError> promise;
    std::shared_future<WorkOrError> future;
    bool mine = false;
    {
      std::lock_guard lock(mu_);
      auto it = jobs_.find(lease.job_id());
      if (it == jobs_.end()) {
        future = promise.get_future().share();
        jobs_.emplace(lease.job_id(), future);
        order_.push_back(lease.job_id());
        if (order_.size() > kJobsCached) {
          jobs_.erase(order_.front());
          order_.pop_front();
        }
        mine = true;
      } else {
        future = it->second;
      }
    }
    if (mine) promise.set_value(Prepare(lease));
    WorkOrError work = future.get();
    if (!work.ok()) {  // do not keep a failure: the next lease tries again
      std::lock_guard lock(mu_);
      jobs_.erase(lease.job_id());
      std::erase(order_, lease.job_id());
    }
    return work;
  }

 private:
  WorkOrError Prepare(const v1::BlockLease& lease) {
    const auto start = Clock::now();
    absl::StatusOr<StoredScene> stored = FetchScene(stub_, token_, lease.scene_sha256());
    if (!stored.ok()) return stored.status();
    if (lease.options().has_viewfactors()) return PrepareViewFactors(lease, *std::move(stored));
    absl::StatusOr<JobOptions> options = FromProto(lease.options());
    if (!options.ok()) return options.status();
    absl::StatusOr<ImportOptions> import = FromProto(lease.options().import_options());
    if (!import.ok()) return import.status();
    absl::StatusOr<Scene> scene = LoadStoredScene(*stored, *import);
    if (!scene.ok()) return scene.status();
    absl::StatusOr<std::unique_ptr<PreparedJob>> prepared = PrepareJob(*std::move(scene), *options);
    if (!prepared.ok()) return prepared.status();
    auto work = std::make_shared<PreparedWork>();
    work->job = *std::move(prepared);
    if (work->job->Unknowns() != lease.patch_count()) {
      return absl::FailedPreconditionError(
          absl::StrCat("job ", lease.job_id(), ": meshed ", work->job->Unknowns(),
                       " unknowns, the server has ", lease.patch_count()));
    }
    work->builder = MakeRowBuilder(work->job->rows, options->form_factors);
    work->cutoff = options->form_factors.cutoff;
    spdlog::info("job {}: scene {} prepared, {} patches ({:.2f} s)", lease.job_id(), stored->name,
                 lease.patch_count(), std::chrono::duration<double>(Clock::now() - start).count());
    return work;
  }

  // A view-factor job: its surfaces and the plan of rows the lease pins; each block is built
  // on the one thread that took its lease.
  static WorkOrError PrepareViewFactors(const v1::BlockLease& lease, StoredScene stored) {
    absl::StatusOr<std::unique_ptr<ViewFactorWork>> prepared =
        PrepareViewFactorWork(lease.options(), std::move(stored), /*threads=*/1);
    if (!prepared.ok()) return prepared.status();
    if ((*prepared)->surfaces.radiating != lease.patch_count()) {
      return absl::FailedPreconditionError(
          absl::StrCat("job ", lease.job_id(), ": ", (*prepared)->surfaces.radiating,
                       " surfaces, the server has ", lease.patch_count()));
    }
    auto work = std::make_shared<PreparedWork>();
    work->view_factors = *std::move(prepared);
    spdlog::info("job {}: view-factor model prepared, {} surfaces", lease.job_id(),
                 lease.patch_count());
    return work;
  }

  v1::Worker::Stub& stub_;
  const std::string token_;
  std::mutex mu_;
  std::map<std::string, std::shared_future<WorkOrError>> jobs_;
  std::deque<std::string> order_;
};

// Leases received and not yet taken by a thread.
class LeaseQueue {
 public:
  void Push(v1::BlockLease lease) {
    std::lock_guard lock(mu_);
    leases_.push_back(std::move(lease));
    cv_.notify_one();
  }
  void Close() {
    std::lock_guard lock(mu_);
    closed_ = true;
    cv_.notify_all();
  }
  // The next lease; nullopt once closed (or stopping) and drained.
  std::optional<v1::BlockLease> Pop(const std::atomic<bool>& stop) {
    std::unique_lock lock(mu_);
    while (leases_.empty() && !closed_ && !stop) cv_.wait_for(lock, kPoll);
    if (leases_.empty() || stop) return std::nullopt;
    v1::BlockLease lease = std::move(leases_.front());
    leases_.pop_front();
    return lease;
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<v1::BlockLease> leases_;
  bool closed_ = false;
};

// A thread's row scratch, sized for the job it last built.
struct Scratch {
  std::unique_ptr<RowAccumulator> row;
  size_t n = 0;
};

// Builds the block of `lease` into a result message.
v1::BlockResult BuildBlock(const v1::BlockLease& lease, const PreparedWork& work, Scratch& scratch,
                           int delay_ms) {
  const auto start = Clock::now();
  StoredRowBlock rows;
  if (work.view_factors) {
    rows = BuildViewFactorBlock(*work.view_factors->plan, lease.first_row(), lease.row_count());
  } else {
    const size_t n = work.job->Unknowns();
    if (!scratch.row || scratch.n != n) {
      scratch.row = std::make_unique<RowAccumulator>(n);
      scratch.n = n;
    }
    rows.block = BuildRowBlock(*work.builder, work.job->rows, work.cutoff, lease.first_row(),
                               lease.row_count(), *scratch.row, rows.stats);
  }
  if (delay_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  v1::BlockResult result = PackRowBlock(lease, rows);
  result.set_build_seconds(std::chrono::duration<double>(Clock::now() - start).count());
  if (result.ByteSizeLong() > kMaxResultBytes) {
    result.clear_rows_zstd();
    result.clear_sha256();
    result.set_too_large(true);
  }
  return result;
}

std::string HostName() {
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  return absl::StrCat(name, ":", getpid());
}

// One connection: hello, then leases in (reader thread) and blocks out (the OpenMP
// threads), until the stream ends. Returns its final status; *welcomed when it got in.
grpc::Status Session(v1::Worker::Stub& stub, const WorkerNodeOptions& options, JobCache& cache,
                     int threads, const std::atomic<bool>& stop, bool* welcomed) {
  grpc::ClientContext context;
  AddAuth(context, options.worker_token);
  auto stream = stub.Connect(&context);
  v1::WorkerMessage hello;
  hello.mutable_hello()->set_threads(threads);
  hello.mutable_hello()->set_name(HostName());
  v1::ServerMessage message;
  if (!stream->Write(hello) || !stream->Read(&message) || !message.has_welcome()) {
    return stream->Finish();
  }
  *welcomed = true;
  spdlog::info("registered with {} as worker {}, {} thread(s)", options.server,
               message.welcome().worker_id(), threads);
  LeaseQueue queue;
  std::thread reader([&] {
    v1::ServerMessage in;
    while (stream->Read(&in)) {
      if (in.has_lease()) queue.Push(in.lease());
    }
    queue.Close();
  });
  std::mutex write_mu;  // one write at a time: the builders' results and the heartbeats
  std::condition_variable session_over;
  bool building = true;  // guarded by write_mu
  std::thread heartbeat([&] {  // "still here", also while every thread builds
    v1::WorkerMessage beat;
    beat.mutable_heartbeat();
    std::unique_lock lock(write_mu);
    while (!session_over.wait_for(lock, kHeartbeatInterval, [&] { return !building; })) {
      if (!stream->Write(beat)) return;
    }
  });
  ParallelFor(threads, 1, threads, [&](int64_t, int64_t) {
    Scratch scratch;
    while (std::optional<v1::BlockLease> lease = queue.Pop(stop)) {
      WorkOrError work = cache.Get(*lease);
      if (!work.ok()) {
        spdlog::error("job {}: cannot prepare: {}", lease->job_id(),
                      std::string(work.status().message()));
        context.TryCancel();  // the server leases the block to someone else
        return;
      }
      spdlog::info("building row block {} of job {} (rows {}..{}, lease {})", lease->block_index(),
                   lease->job_id(), lease->first_row(), lease->first_row() + lease->row_count() - 1,
                   lease->lease_id());
      v1::WorkerMessage out;
      *out.mutable_result() = BuildBlock(*lease, **work, scratch, options.block_delay_ms);
      std::lock_guard lock(write_mu);
      if (!stream->Write(out)) return;
      spdlog::info("sent row block {} of job {}", lease->block_index(), lease->job_id());
    }
  });
  {
    std::lock_guard lock(write_mu);
    building = false;
  }
  session_over.notify_all();
  heartbeat.join();
  context.TryCancel();  // stopping, or the stream already ended: end the reader
  reader.join();
  return stream->Finish();
}

}  // namespace

int RunWorkerNode(const WorkerNodeOptions& options, const std::atomic<bool>& stop) {
  const std::shared_ptr<grpc::ChannelCredentials> credentials =
      ChannelCredentialsFromFile(options.tls_ca, options.tls_cert, options.tls_key);
  if (!credentials) {
    spdlog::error("cannot read --tls-ca {} / --tls-cert {} / --tls-key {}", options.tls_ca,
                  options.tls_cert, options.tls_key);
    return 1;
  }
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(kMaxMessageBytes);
  args.SetMaxSendMessageSize(kMaxMessageBytes);
  if (!options.tls_server_name.empty()) args.SetSslTargetNameOverride(options.tls_server_name);
  auto stub = v1::Worker::NewStub(grpc::CreateCustomChannel(options.server, credentials, args));
  JobCache cache(*stub, options.worker_token);
  const int threads = ThreadCount(options.threads);
  auto backoff = std::chrono::milliseconds(500);
  while (!stop) {
    bool welcomed = false;
    const grpc::Status status = Session(*stub, options, cache, threads, stop, &welcomed);
    if (status.error_code() == grpc::StatusCode::UNAUTHENTICATED) {
      spdlog::error("server {} refused this worker: UNAUTHENTICATED: {}", options.server,
                    status.error_message());
      return 2;
    }
    if (stop) break;
    if (welcomed) backoff = std::chrono::milliseconds(500);
    spdlog::warn("connection to {} ended ({}: {}); reconnecting in {} ms", options.server,
                 static_cast<int>(status.error_code()), status.error_message(), backoff.count());
    for (auto waited = std::chrono::milliseconds(0); waited < backoff && !stop; waited += kPoll) {
      std::this_thread::sleep_for(kPoll);
    }
    backoff = std::min(backoff * 2, std::chrono::milliseconds(10000));
  }
  spdlog::info("worker stopped");
  return 0;
}

}  // namespace radflux
