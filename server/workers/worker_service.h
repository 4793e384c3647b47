// WorkerService: the radflux.v1.Worker gRPC service, the server's end of the worker nodes.
// Each Connect stream is one worker: a sync handler thread writes its leases (at most its
// thread count at once) while a reader thread hands its results to the RowFarm. A worker
// whose result is malformed or mismatched is dropped with the reason logged; its blocks,
// like those of a worker that disconnects, are leased again. Calls must carry the worker
// token (not the client token); with no worker token configured, workers are refused
// whenever a client token is set (a client token must never register a worker).
#pragma once

#include <grpcpp/grpcpp.h>

#include <string>

#include "radflux/v1/worker.grpc.pb.h"
#include "server/jobs/job_manager.h"
#include "server/workers/row_farm.h"

namespace radflux {

class WorkerService final : public v1::Worker::Service {
 public:
  WorkerService(RowFarm& farm, JobManager& manager, std::string worker_token, bool client_token_set)
      : farm_(farm),
        manager_(manager),
        worker_token_(std::move(worker_token)),
        client_token_set_(client_token_set) {}

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
  const bool client_token_set_;
};

}  // namespace radflux
