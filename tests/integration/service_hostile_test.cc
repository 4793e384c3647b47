// radfluxd against hostile clients (issue 22): requests built to crash, confuse or exhaust
// the server are refused with a clear status, and the server keeps serving.
#include <grpcpp/grpcpp.h>
#include <grpcpp/impl/client_unary_call.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

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

// --max-edge 1e-300 bounds the Cornell box past the largest double: refused saying so,
// not with the int64 it wrapped to ("would mesh -9223372036854775808 patches").
TEST_F(HostileTest, AMaxEdgeFarBeyondTheLimitNamesAHugeCountNotANegativeOne) {
  StartServer({"--max-patches", "100000"});
  const std::string sha = UploadCornell();
  v1::SolveOptions options;
  options.set_max_edge(1e-300);
  v1::Job job;
  const grpc::Status status = Submit(options, &job, sha);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(status.error_message(),
            "job would mesh more than 1e+308 patches; this server allows at most 100000 "
            "(--max-patches)");
  options.set_max_edge(1e-150);  // a bound a double holds, past any int64
  const grpc::Status finite = Submit(options, &job, sha);
  EXPECT_EQ(finite.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(finite.error_message().rfind("job would mesh about ", 0), 0) << finite.error_message();
  EXPECT_NE(finite.error_message().find("e+30"), std::string::npos) << finite.error_message();
}

// A SubmitJob whose bytes are no SubmitJobRequest is a bad argument, not an unknown method.
TEST_F(HostileTest, AMalformedSubmitJobIsAnInvalidArgument) {
  StartServer();
  auto channel = grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials());
  const grpc::internal::RpcMethod method("/radflux.v1.Radiosity/SubmitJob",
                                         grpc::internal::RpcMethod::NORMAL_RPC);
  const std::string garbage = "\xff\xff\xff\xff\xff\xff\xff\xff\xff\x0f garbage";
  grpc::Slice slice(garbage);
  const grpc::ByteBuffer request(&slice, 1);
  grpc::ByteBuffer response;
  auto context = Context();
  const grpc::Status status =
      grpc::internal::BlockingUnaryCall(channel.get(), method, context.get(), request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  ExpectServerAlive();
}

// With --max-concurrent-uploads 1, an upload while another is open is refused with
// RESOURCE_EXHAUSTED naming the flag; once the open one ends its slot is free again.
TEST_F(HostileTest, UploadsBeyondTheConcurrentLimitAreRefusedNamingTheLimit) {
  StartServer({"--max-concurrent-uploads", "1"});
  v1::SceneChunk chunk;
  v1::SceneRef open_ref;
  std::unique_ptr<grpc::ClientContext> open_context;
  std::unique_ptr<grpc::ClientWriter<v1::SceneChunk>> open;
  grpc::Status refused;
  // Until the server has seen the open upload a second one may still pass; then it may not.
  // A second one that reaches the server first takes the slot and the open one is refused
  // instead: then none is ever refused, and the round starts again with a new open one (as
  // it does when the new open one is refused at once, the last round's still in its slot).
  for (int round = 0; round < 10 && refused.ok(); ++round) {
    if (open != nullptr) {  // the last round's, refused: ended before its context goes
      open->WritesDone();
      open->Finish();
      open.reset();
    }
    open_context = Context();
    open = stub_->UploadScene(open_context.get(), &open_ref);
    chunk.Clear();
    chunk.mutable_header()->set_name("cornell_box.obj");
    chunk.mutable_header()->set_obj_size(kObj.size());
    chunk.mutable_header()->set_mtl_size(kMtl.size());
    chunk.set_data(kObj);
    if (!open->Write(chunk)) {  // refused at once: the last round's upload still held the
      usleep(10'000);           // slot (it is freed just after its client sees its status)
      continue;
    }
    for (int attempt = 0; attempt < 200 && refused.ok(); ++attempt) {
      v1::SceneRef ref;
      refused = Upload(kObj, kMtl, &ref);
      if (refused.ok()) usleep(10'000);
    }
  }
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << refused.error_message();
  EXPECT_EQ(refused.error_message(),
            "1 uploads are in progress, the most this server takes at once "
            "(--max-concurrent-uploads); try again when one ends");
  chunk.Clear();
  chunk.set_data(kMtl);
  ASSERT_TRUE(open->Write(chunk));
  open->WritesDone();
  const grpc::Status finished = open->Finish();
  EXPECT_TRUE(finished.ok()) << finished.error_message();
  // The slot is freed when the server is done with the call (just after the client sees
  // its status): a new upload is served then.
  grpc::Status again = refused;
  for (int attempt = 0; attempt < 500 && !again.ok(); ++attempt) {
    v1::SceneRef ref;
    again = Upload(kObj, kMtl, &ref);
    if (!again.ok()) usleep(10'000);
  }
  EXPECT_TRUE(again.ok()) << again.error_message();
}

}  // namespace
}  // namespace radflux
