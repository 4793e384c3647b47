// WorkerService: the radflux.v1.Worker gRPC service, the server's end of the worker nodes.
// Each Connect stream is one worker: a sync handler thread writes its leases (at most its
// thread count at once) while a reader thread hands its results to the RowFarm. A worker
// whose result is malformed or mismatched is dropped with the reason logged; its blocks,
// like those of a worker that disconnects, are leased again. Calls must carry the worker
// token (not the client token); with no worker token configured, workers are refused
// unless the server was started with --allow-workers-without-token (then anyone who
// reaches the port may be a worker: their rows are still checked, see RowFarm).
#pragma once

#include <grpcpp/grpcpp.h>

#include <string>

#include "radflux/v1/worker.grpc.pb.h"
#include "server/jobs/job_manager.h"
#include "server/workers/row_farm.h"

namespace radflux {

class WorkerService final : public v1::Worker::Service {
 public:
  // `allow_without_token`: with an empty `worker_token`, accept any worker (else refuse all).
  WorkerService(RowFarm& farm, JobManager& manager, std::string worker_token,
                bool allow_without_token)
      : farm_(farm),
        manager_(manager),
        worker_token_(std::move(worker_token)),
        allow_without_token_(allow_without_token) {}

  grpc::Status Connect(
      grpc::ServerContext* context,
      grpc::ServerReaderWriter<v1::ServerMessage, v1::WorkerMessage>* stream) override;
  grpc::Status FetchScene(grpc::ServerContext* context, const v1::FetchSceneRequest* request,
                          grpc::ServerWriter<v1::SceneChunk>* writer) override;

 private:
  grpc::Status Authenticate(const grpc::ServerContext& context) const;

  RowFarm& farm_;
  JobManager& manager_;
  const std::string worker_token_;
  const bool allow_without_token_;
};

}  // namespace radflux
