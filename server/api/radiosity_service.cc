#include "server/api/radiosity_service.h"

#include <functional>

#include "absl/strings/str_cat.h"
#include "server/api/rpc_guard.h"
#include "server/jobs/watch_reactor.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

// A server stream that ends at once with an error.
template <typename T>
class ErrorWriteReactor final : public grpc::ServerWriteReactor<T> {
 public:
  explicit ErrorWriteReactor(const grpc::Status& status) { this->Finish(status); }
  void OnDone() override { delete this; }
};

// Streams an upload to disk as its chunks arrive (SceneUpload: size checked per chunk,
// written off the reactor thread, one chunk in flight), then checks and stores the scene.
// A failed or cancelled upload's temp files are removed when it ends.
class UploadReactor final : public grpc::ServerReadReactor<v1::SceneChunk> {
 public:
  // Holds one of `uploads` (already counted by the caller) until the upload is done.
  UploadReactor(JobManager& manager, WorkQueue& work, const Principal& caller,
                v1::SceneRef* response, std::atomic<int>& uploads)
      : manager_(manager), work_(work), caller_(caller), response_(response), uploads_(uploads) {
    StartRead(&chunk_);
  }

  void OnReadDone(bool ok) override {
    work_.Post([this, ok] { ok ? Take() : Complete(); });
  }

  void OnDone() override {
    uploads_.fetch_sub(1);
    delete this;
  }

 private:
  // Writes the chunk just read and reads the next; an error ends the upload with it.
  void Take() {
    const absl::Status taken = GuardCall("UploadScene", [&] { return TakeChunk(); });
    if (taken.ok()) {
      StartRead(&chunk_);
    } else {
      End(taken);
    }
  }

  absl::Status TakeChunk() {
    if (!upload_) {
      if (!chunk_.has_header())
        return absl::InvalidArgumentError("the first chunk of an upload must carry its header");
      header_ = chunk_.header();
      absl::StatusOr<std::unique_ptr<SceneUpload>> upload = manager_.StartUpload(header_);
      if (!upload.ok()) return upload.status();
      upload_ = *std::move(upload);
    }
    return upload_->Append(chunk_.data());
  }

  // The stream ended (or was cancelled): check and store the scene.
  void Complete() {
    absl::StatusOr<v1::SceneRef> ref =
        GuardCall("UploadScene", [&]() -> absl::StatusOr<v1::SceneRef> {
          if (!upload_) return absl::InvalidArgumentError("empty upload");
          return manager_.AddScene(header_, *upload_, caller_);
        });
    if (ref.ok()) *response_ = *ref;
    End(ref.status());
  }

  // Removes what the upload left on disk (nothing once stored) and ends the call.
  void End(const absl::Status& status) {
    upload_.reset();
    Finish(ToGrpcStatus(status));
  }

  JobManager& manager_;
  WorkQueue& work_;
  const Principal& caller_;
  v1::SceneRef* response_;
  std::atomic<int>& uploads_;
  v1::SceneChunk chunk_;
  v1::SceneHeader header_;
  std::unique_ptr<SceneUpload> upload_;  // from the first chunk on
};

// Streams messages produced off the reactor thread by `produce` (a result's chunks, a
// scene's chunks), one write in flight, Finish exactly once.
template <typename T>
class ChunkStreamReactor final : public grpc::ServerWriteReactor<T> {
 public:
  ChunkStreamReactor(WorkQueue& work, std::function<absl::StatusOr<std::vector<T>>()> produce) {
    work.Post([this, produce = std::move(produce)] {
      absl::StatusOr<std::vector<T>> chunks = GuardCall("a streamed call", produce);
      {
        std::lock_guard lock(mu_);
        if (chunks.ok())
          chunks_ = *std::move(chunks);
        else
          status_ = ToGrpcStatus(chunks.status());
      }
      Next();
    });
  }

  void OnWriteDone(bool ok) override {
    {
      std::lock_guard lock(mu_);
      if (!ok) cancelled_ = true;
    }
    Next();
  }
  void OnCancel() override {
    std::lock_guard lock(mu_);
    cancelled_ = true;
  }
  void OnDone() override { delete this; }

 private:
  void Next() {
    std::unique_lock lock(mu_);
    if (cancelled_ || !status_.ok() || next_ == chunks_.size()) {
      const grpc::Status status = cancelled_ ? grpc::Status::CANCELLED : status_;
      lock.unlock();
      this->Finish(status);
      return;
    }
    const T* chunk = &chunks_[next_++];
    lock.unlock();
    this->StartWrite(chunk);
  }

  std::mutex mu_;
  std::vector<T> chunks_;
  size_t next_ = 0;
  grpc::Status status_;
  bool cancelled_ = false;
};

// A stored scene as the chunks GetScene streams (see ToSceneChunks).
absl::StatusOr<std::vector<v1::SceneChunk>> SceneChunks(JobManager& manager,
                                                        const std::string& sha256,
                                                        const Principal& caller) {
  absl::StatusOr<StoredScene> scene = manager.GetScene(sha256, caller);
  if (!scene.ok()) return scene.status();
  return ToSceneChunks(*scene, sha256);
}

// INVALID_ARGUMENT for a snapshot cadence < 0 or bands that are not distinct values 0..2.
grpc::Status CheckWatchRequest(const v1::WatchJobRequest& request) {
  if (request.snapshot_every() < 0) {
    return grpc::Status(
        grpc::StatusCode::INVALID_ARGUMENT,
        absl::StrCat("snapshot_every must be >= 0, not ", request.snapshot_every()));
  }
  bool seen[3] = {false, false, false};
  for (int band : request.bands()) {
    if (band < 0 || band > 2 || seen[band]) {
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          absl::StrCat("bands must be distinct values of 0 (red), 1 (green), "
                                       "2 (blue); got ",
                                       band));
    }
    seen[band] = true;
  }
  return grpc::Status::OK;
}

// A unary call: the caller identified on the reactor thread, `work(caller)` on the work
// queue.
template <typename Work>
grpc::ServerUnaryReactor* RunUnary(grpc::CallbackServerContext* context,
                                   const Principals& principals, WorkQueue& queue, Work work) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  const Principal* caller = nullptr;
  if (grpc::Status auth = principals.Identify(*context, &caller); !auth.ok()) {
    reactor->Finish(auth);
    return reactor;
  }
  queue.Post([reactor, caller, work = std::move(work)] {
    reactor->Finish(ToGrpcStatus(GuardCall("a unary call", [&] { return work(*caller); })));
  });
  return reactor;
}

}  // namespace

grpc::ServerReadReactor<v1::SceneChunk>* RadiosityService::UploadScene(
    grpc::CallbackServerContext* context, v1::SceneRef* response) {
  class Refuse final : public grpc::ServerReadReactor<v1::SceneChunk> {
   public:
    explicit Refuse(const grpc::Status& s) { Finish(s); }
    void OnDone() override { delete this; }
  };
  const Principal* caller = nullptr;
  if (grpc::Status auth = principals_.Identify(*context, &caller); !auth.ok()) {
    return new Refuse(auth);
  }
  const int limit = manager_.options().max_concurrent_uploads;
  if (uploads_.fetch_add(1) >= limit) {
    uploads_.fetch_sub(1);
    return new Refuse(grpc::Status(
        grpc::StatusCode::RESOURCE_EXHAUSTED,
        absl::StrCat(limit, " uploads are in progress, the most this server takes at once "
                            "(--max-concurrent-uploads); try again when one ends")));
  }
  return new UploadReactor(manager_, work_, *caller, response, uploads_);
}

grpc::ServerUnaryReactor* RadiosityService::SubmitJob(grpc::CallbackServerContext* context,
                                                      const grpc::ByteBuffer* raw_request,
                                                      grpc::ByteBuffer* response) {
  return RunUnary(context, principals_, work_, [this, raw_request, response](const Principal& caller) {
    v1::SubmitJobRequest request;
    grpc::ByteBuffer bytes(*raw_request);  // shares the slices; Deserialize consumes it
    if (!grpc::SerializationTraits<v1::SubmitJobRequest>::Deserialize(&bytes, &request).ok()) {
      return absl::InvalidArgumentError("malformed SubmitJobRequest");
    }
    absl::StatusOr<v1::Job> job = manager_.Submit(request, caller);
    if (!job.ok()) return job.status();
    bool own_buffer = false;
    if (!grpc::SerializationTraits<v1::Job>::Serialize(*job, response, &own_buffer).ok()) {
      return absl::InternalError("cannot serialize the submitted job");
    }
    return absl::OkStatus();
  });
}

grpc::ServerWriteReactor<grpc::ByteBuffer>* RadiosityService::WatchJob(
    grpc::CallbackServerContext* context, const grpc::ByteBuffer* raw_request) {
  using Error = ErrorWriteReactor<grpc::ByteBuffer>;
  const Principal* caller = nullptr;
  if (grpc::Status auth = principals_.Identify(*context, &caller); !auth.ok()) {
    return new Error(auth);
  }
  v1::WatchJobRequest request;
  grpc::ByteBuffer bytes(*raw_request);  // shares the slices; Deserialize consumes it
  if (!grpc::SerializationTraits<v1::WatchJobRequest>::Deserialize(&bytes, &request).ok()) {
    return new Error(grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, "malformed WatchJobRequest"));
  }
  if (grpc::Status valid = CheckWatchRequest(request); !valid.ok()) return new Error(valid);
  absl::StatusOr<std::shared_ptr<JobHub>> hub =
      GuardCall("WatchJob", [&] { return manager_.Hub(request.job_id(), *caller); });
  if (!hub.ok()) return new Error(ToGrpcStatus(hub.status()));
  return new WatchReactor(*std::move(hub), request);
}

grpc::ServerWriteReactor<v1::ResultChunk>* RadiosityService::GetResult(
    grpc::CallbackServerContext* context, const v1::GetResultRequest* request) {
  const Principal* caller = nullptr;
  if (grpc::Status auth = principals_.Identify(*context, &caller); !auth.ok()) {
    return new ErrorWriteReactor<v1::ResultChunk>(auth);
  }
  return new ChunkStreamReactor<v1::ResultChunk>(
      work_, [this, caller, job_id = request->job_id(), report_only = request->report_only()] {
        return manager_.Result(job_id, *caller, report_only);
      });
}

grpc::ServerUnaryReactor* RadiosityService::GetJob(grpc::CallbackServerContext* context,
                                                   const v1::GetJobRequest* request,
                                                   v1::Job* response) {
  return RunUnary(context, principals_, work_, [this, request, response](const Principal& caller) {
    absl::StatusOr<v1::Job> job = manager_.Get(request->job_id(), caller);
    if (job.ok()) *response = *job;
    return job.status();
  });
}

grpc::ServerWriteReactor<v1::SceneChunk>* RadiosityService::GetScene(
    grpc::CallbackServerContext* context, const v1::GetSceneRequest* request) {
  const Principal* caller = nullptr;
  if (grpc::Status auth = principals_.Identify(*context, &caller); !auth.ok()) {
    return new ErrorWriteReactor<v1::SceneChunk>(auth);
  }
  return new ChunkStreamReactor<v1::SceneChunk>(
      work_, [this, caller, sha = request->sha256()] { return SceneChunks(manager_, sha, *caller); });
}

grpc::ServerUnaryReactor* RadiosityService::CancelJob(grpc::CallbackServerContext* context,
                                                      const v1::CancelJobRequest* request,
                                                      v1::Job* response) {
  return RunUnary(context, principals_, work_, [this, request, response](const Principal& caller) {
    absl::StatusOr<v1::Job> job = manager_.Cancel(request->job_id(), caller);
    if (job.ok()) *response = *job;
    return job.status();
  });
}

grpc::ServerUnaryReactor* RadiosityService::ListJobs(grpc::CallbackServerContext* context,
                                                     const v1::ListJobsRequest* request,
                                                     v1::ListJobsResponse* response) {
  return RunUnary(context, principals_, work_, [this, request, response](const Principal& caller) {
    absl::StatusOr<v1::ListJobsResponse> list = manager_.List(*request, caller);
    if (list.ok()) *response = *list;
    return list.status();
  });
}

}  // namespace radflux
