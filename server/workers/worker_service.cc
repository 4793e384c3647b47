#include "server/workers/worker_service.h"

#include <spdlog/spdlog.h>

#include <atomic>
#include <thread>

#include "server/api/auth.h"
#include "server/api/rpc_guard.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

constexpr std::chrono::milliseconds kLeasePoll{200};  // how often the writer checks the stream
constexpr int kMaxWorkerThreads = 4096;

// Workers (holders of the worker token) fetch the scene of any job whose rows they build:
// an admin's view of the scenes, and nothing else of the client API.
const Principal& WorkersPrincipal() {
  static const Principal workers{"workers", /*admin=*/true, {}};
  return workers;
}

}  // namespace

grpc::Status WorkerService::Authenticate(const grpc::ServerContext& context) const {
  if (worker_token_.empty() && !allow_without_token_) {
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                        "this server takes no workers: it has no --worker-token (start it with "
                        "--worker-token TOKEN and the workers with the same --worker-token, or "
                        "with --allow-workers-without-token to let any worker in)");
  }
  return CheckBearerToken(context, worker_token_, "--worker-token");
}

grpc::Status WorkerService::Connect(
    grpc::ServerContext* context,
    grpc::ServerReaderWriter<v1::ServerMessage, v1::WorkerMessage>* stream) {
  if (grpc::Status auth = Authenticate(*context); !auth.ok()) {
    spdlog::warn("worker from {} refused: {}", context->peer(), auth.error_message());
    return auth;
  }
  v1::WorkerMessage first;
  if (!stream->Read(&first)) return grpc::Status::CANCELLED;
  if (!first.has_hello()) {
    return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, "the first message must be hello");
  }
  const int threads = std::clamp(first.hello().threads(), 1, kMaxWorkerThreads);
  const std::string name = first.hello().name().empty() ? context->peer() : first.hello().name();
  const uint64_t id = farm_.AddWorker(threads, name);
  spdlog::info("worker {} joined: {} ({}), {} thread(s)", id, name, context->peer(), threads);
  v1::ServerMessage welcome;
  welcome.mutable_welcome()->set_worker_id(id);
  if (!stream->Write(welcome)) {
    farm_.RemoveWorker(id, "left before its welcome");
    return grpc::Status::CANCELLED;
  }

  // Reader: results in, until the stream ends or a result drops the worker.
  std::atomic<bool> done{false};
  grpc::Status drop = grpc::Status::OK;  // written by the reader before `done`
  std::thread reader([&] {
    v1::WorkerMessage message;
    while (stream->Read(&message)) {
      farm_.Heard(id);
      if (!message.has_result()) continue;
      const absl::Status accepted =
          GuardCall("a worker result", [&] { return farm_.Accept(id, message.result()); });
      if (!accepted.ok()) {
        drop = ToGrpcStatus(accepted);  // the writer returns it once it sees `done`
        break;
      }
    }
    done = true;
  });
  // Writer (this thread): leases out while the worker has free threads.
  while (!done && !context->IsCancelled()) {
    std::optional<v1::BlockLease> lease = farm_.NextLease(id, kLeasePoll);
    if (!lease) continue;
    v1::ServerMessage message;
    *message.mutable_lease() = *std::move(lease);
    if (!stream->Write(message)) break;
  }
  if (!done) context->TryCancel();  // ends the reader's Read if the writer stopped first
  reader.join();
  if (!drop.ok()) {
    spdlog::error("worker {} ({}) dropped: {}", id, name, drop.error_message());
    farm_.RemoveWorker(id, "was dropped (" + drop.error_message() + ")");
    return drop;
  }
  spdlog::info("worker {} ({}) left", id, name);
  farm_.RemoveWorker(id, "disconnected");
  return grpc::Status::OK;
}

grpc::Status WorkerService::FetchScene(grpc::ServerContext* context,
                                       const v1::FetchSceneRequest* request,
                                       grpc::ServerWriter<v1::SceneChunk>* writer) {
  if (grpc::Status auth = Authenticate(*context); !auth.ok()) return auth;
  absl::StatusOr<StoredScene> scene = manager_.GetScene(request->sha256(), WorkersPrincipal());
  if (!scene.ok()) return ToGrpcStatus(scene.status());
  for (const v1::SceneChunk& chunk : ToSceneChunks(*scene, request->sha256())) {
    if (!writer->Write(chunk)) return grpc::Status::CANCELLED;
  }
  return grpc::Status::OK;
}

}  // namespace radflux
