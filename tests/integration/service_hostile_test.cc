// radfluxd against hostile clients (issue 22): requests built to crash, confuse or exhaust
// the server are refused with a clear status, and the server keeps serving.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <cstdint>
#include <limits>

#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"
#include "wire/scene_hash.h"

namespace radflux {
namespace {

using testing::kMtl;
using testing::kObj;

class HostileTest : public testing::ServiceFixture {
 public:
  // The server process is still running and still answers: a full upload succeeds.
  void ExpectServerAlive() {
    ASSERT_EQ(kill(server_->pid(), 0), 0) << "radfluxd died";
    v1::SceneRef ref;
    const grpc::Status status = Upload(kObj, kMtl, &ref, SceneContentHash(kObj, kMtl));
    EXPECT_TRUE(status.ok()) << status.error_message();
    EXPECT_EQ(ref.sha256(), SceneContentHash(kObj, kMtl));
  }

  // Uploads one chunk carrying `header` and `data`.
  grpc::Status UploadRaw(const v1::SceneHeader& header, const std::string& data) {
    v1::SceneRef ref;
    auto context = Context();
    auto writer = stub_->UploadScene(context.get(), &ref);
    v1::SceneChunk chunk;
    *chunk.mutable_header() = header;
    chunk.set_data(data);
    writer->Write(chunk);
    writer->WritesDone();
    return writer->Finish();
  }
};

// obj_size + mtl_size wraps to 1: the sum of the sizes was unchecked and SplitScenePayload
// threw std::out_of_range on a work-queue thread, aborting radfluxd.
TEST_F(HostileTest, UploadSizesThatOverflowAreRefusedAndTheServerLives) {
  StartServer();
  v1::SceneHeader header;
  header.set_name("wrap.obj");
  header.set_obj_size(std::numeric_limits<uint64_t>::max());
  header.set_mtl_size(2);
  const grpc::Status status = UploadRaw(header, "x");
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_NE(status.error_message().find("overflow"), std::string::npos) << status.error_message();
  ExpectServerAlive();

  // The mesh size wrapping the texts' sum to 0 is refused as well (both forms declared).
  header.set_obj_size(1);
  header.set_mtl_size(0);
  header.set_mesh_size(std::numeric_limits<uint64_t>::max());
  EXPECT_EQ(UploadRaw(header, "").error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  ExpectServerAlive();
}

// A request_id names one request: a retry gets its job, the same id with another scene or
// other options is refused (it silently returned the earlier job), and ids are bounded (a
// 4 MB id broke `radflux list` for every client).
TEST_F(HostileTest, RequestIdReusedForAnotherRequestIsRefusedAndIdsAreBounded) {
  StartServer();
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = testing::SmallOptions(100, "jacobi");
  v1::Job first;
  ASSERT_TRUE(Submit(options, &first, sha, "id-1").ok());
  v1::Job retry;
  ASSERT_TRUE(Submit(options, &retry, sha, "id-1").ok());
  EXPECT_EQ(retry.job_id(), first.job_id());

  v1::SolveOptions other = options;
  other.set_rays(64);
  v1::Job refused;
  const grpc::Status status = Submit(other, &refused, sha, "id-1");
  EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION) << status.error_message();
  EXPECT_NE(status.error_message().find(first.job_id()), std::string::npos)
      << status.error_message();
  EXPECT_TRUE(refused.job_id().empty());

  v1::Job job;
  EXPECT_EQ(Submit(options, &job, sha, std::string(129, 'x')).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Submit(options, &job, sha, std::string(128, 'x')).ok());
}

}  // namespace
}  // namespace radflux
