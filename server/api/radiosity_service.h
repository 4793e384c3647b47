// RadiosityService: the radflux.v1.Radiosity gRPC service (callback API). A thin shell:
// it maps each call to its principal (Principals::Identify), moves blocking work onto a
// WorkQueue, and calls the JobManager for that principal; conversions live in proto_convert.
#pragma once

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <string>

#include "radflux/v1/radiosity.grpc.pb.h"
#include "server/api/principals.h"
#include "server/jobs/job_manager.h"
#include "server/jobs/work_queue.h"

namespace radflux {

// WatchJob is a raw method: its reactor writes events serialized once for all watchers.
// SubmitJob is raw so that bytes that are no SubmitJobRequest get INVALID_ARGUMENT (gRPC's
// own parse answers UNIMPLEMENTED).
class RadiosityService final
    : public v1::Radiosity::WithRawCallbackMethod_SubmitJob<
          v1::Radiosity::WithRawCallbackMethod_WatchJob<v1::Radiosity::CallbackService>> {
 public:
  // `principals` (outliving the service) says who each call comes from.
  RadiosityService(JobManager& manager, WorkQueue& work, const Principals& principals)
      : manager_(manager), work_(work), principals_(principals) {}

  grpc::ServerReadReactor<v1::SceneChunk>* UploadScene(grpc::CallbackServerContext* context,
                                                       v1::SceneRef* response) override;
  // A serialized v1::SubmitJobRequest in, a serialized v1::Job out.
  grpc::ServerUnaryReactor* SubmitJob(grpc::CallbackServerContext* context,
                                      const grpc::ByteBuffer* request,
                                      grpc::ByteBuffer* response) override;
  // A serialized v1::WatchJobRequest in, serialized v1::JobEvents out.
  grpc::ServerWriteReactor<grpc::ByteBuffer>* WatchJob(grpc::CallbackServerContext* context,
                                                       const grpc::ByteBuffer* request) override;
  grpc::ServerWriteReactor<v1::ResultChunk>* GetResult(
      grpc::CallbackServerContext* context, const v1::GetResultRequest* request) override;
  grpc::ServerUnaryReactor* CancelJob(grpc::CallbackServerContext* context,
                                      const v1::CancelJobRequest* request,
                                      v1::Job* response) override;
  grpc::ServerUnaryReactor* ListJobs(grpc::CallbackServerContext* context,
                                     const v1::ListJobsRequest* request,
                                     v1::ListJobsResponse* response) override;
  grpc::ServerUnaryReactor* GetJob(grpc::CallbackServerContext* context,
                                   const v1::GetJobRequest* request, v1::Job* response) override;
  grpc::ServerWriteReactor<v1::SceneChunk>* GetScene(grpc::CallbackServerContext* context,
                                                     const v1::GetSceneRequest* request) override;

 private:
  JobManager& manager_;
  WorkQueue& work_;
  const Principals& principals_;
  std::atomic<int> uploads_{0};  // UploadScene calls in progress (--max-concurrent-uploads)
};

}  // namespace radflux
