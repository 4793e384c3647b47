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

// An MTL colour of NaN or inf and a face index past 32 bits were read as 0 and as a valid
// vertex: an upload of either is refused with the loader's own line, and the server serves on.
TEST_F(HostileTest, UploadedNanColourOrWrappingFaceIndexIsRefusedNamingTheLine) {
  StartServer();
  const std::string lamp = "o lamp\nusemtl lamp\nv 0 0 1\nv 0 1 1\nv 1 1 1\n";
  const std::string good_mtl = "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n";
  v1::SceneRef ref;
  grpc::Status status = Upload(lamp + "f 1 2 3\n", "newmtl lamp\nKd nan 0.5 0.5\nKe 1 1 1\n", &ref);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message(), "scene.mtl:2: Kd value 'nan' is not a finite number");
  status = Upload(lamp + "f 1 2 3\n", "newmtl lamp\nKd 0.5 0.5 0.5\nKe inf 1 1\n", &ref);
  EXPECT_EQ(status.error_message(), "scene.mtl:3: Ke value 'inf' is not a finite number");
  status = Upload(lamp + "f 1 2 9223372036854775809\n", good_mtl, &ref);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message(),
            "cornell_box.obj:6: face index 9223372036854775809 is out of range");
  EXPECT_TRUE(Upload(lamp + "f 1 2 3\n", good_mtl, &ref).ok());
  ExpectServerAlive();
}

}  // namespace
}  // namespace radflux
