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

}  // namespace
}  // namespace radflux
