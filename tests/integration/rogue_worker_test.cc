// Untrusted workers (issue 22): a fake worker in the test sends row blocks that lie (NaN,
// offsets that go backwards, made-up rows that look valid, a zstd bomb); the server drops
// each such block, bans the worker from the job, says so in its log and in the job's
// report, and the job still ends with the B an honest run gives, bit for bit. And workers
// need a worker token unless the server is told otherwise.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "server/workers/block_wire.h"
#include "tests/integration/worker_fixture.h"

namespace radflux {
namespace {

using testing::Child;
using testing::Options;
using testing::WorkerTest;

// A worker written by hand on the Worker stream: hello, then leases in, forged results out.
class FakeWorker {
 public:
  FakeWorker(const std::string& address, const std::string& token) {
    stub_ = v1::Worker::NewStub(grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
    if (!token.empty()) context_.AddMetadata("authorization", "Bearer " + token);
    stream_ = stub_->Connect(&context_);
    v1::WorkerMessage hello;
    hello.mutable_hello()->set_threads(1);
    hello.mutable_hello()->set_name("rogue");
    stream_->Write(hello);
  }
  ~FakeWorker() {
    context_.TryCancel();
    stream_->Finish();
  }
  // The next message of the server (false when the stream ended).
  bool Read(v1::ServerMessage* message) { return stream_->Read(message); }
  bool Send(const v1::BlockResult& result) {
    v1::WorkerMessage message;
    *message.mutable_result() = result;
    return stream_->Write(message);
  }
  grpc::Status Finish() { return stream_->Finish(); }

 private:
  std::unique_ptr<v1::Worker::Stub> stub_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<v1::WorkerMessage, v1::ServerMessage>> stream_;
};

// The lies a rogue worker tells.
enum class Lie { kNaN, kBackwardOffsets, kMadeUpRows, kZstdBomb };

// A result for `lease` with its header right and its rows made up: one entry per row in
// the next patch's column (F = 0.25: finite, in range, plausible), then spoiled by `lie`.
v1::BlockResult Forge(const v1::BlockLease& lease, Lie lie) {
  StoredRowBlock rows;
  rows.block.first_row = lease.first_row();
  for (uint32_t i = 0; i < lease.row_count(); ++i) {
    rows.block.Add((lease.first_row() + i + 1) % lease.patch_count(), 0.25f);
    rows.block.EndRow();
  }
  if (lie == Lie::kNaN) rows.block.value[lease.row_count() / 2] = std::nanf("");
  if (lie == Lie::kBackwardOffsets) {  // row 1 starts after row 2: a negative-length row
    rows.block.row_begin[1] = 3;
    rows.block.row_begin[2] = 1;
  }
  v1::BlockResult result = PackRowBlock(lease, rows);
  if (lie == Lie::kZstdBomb) {
    // A zstd frame declaring 2 GiB of content, made of 16384 RLE blocks of 128 KiB each
    // (4 bytes apiece): 64 KiB on the wire.
    std::string bomb = {'\x28', '\xb5', '\x2f', '\xfd', '\x80', '\x38', '\0', '\0', '\0', '\x80'};
    constexpr uint32_t kBlocks = 16384, kRun = 128 << 10;
    for (uint32_t b = 0; b < kBlocks; ++b) {
      const uint32_t header = (b + 1 == kBlocks ? 1u : 0u) | (1u << 1) | (kRun << 3);
      bomb += {static_cast<char>(header & 0xff), static_cast<char>((header >> 8) & 0xff),
               static_cast<char>((header >> 16) & 0xff), '\0'};
    }
    result.set_rows_zstd(bomb);
  }
  return result;
}

// The report of a finished job (GetResult with report_only).
nlohmann::json Report(WorkerTest& t, const std::string& job_id) {
  v1::GetResultRequest request;
  request.set_job_id(job_id);
  request.set_report_only(true);
  auto context = t.Context();
  auto reader = t.stub_->GetResult(context.get(), request);
  std::string report;
  v1::ResultChunk chunk;
  while (reader->Read(&chunk)) {
    if (chunk.part_case() == v1::ResultChunk::kReportJson) report = chunk.report_json();
  }
  EXPECT_TRUE(reader->Finish().ok());
  return nlohmann::json::parse(report);
}

// The server's peak resident memory, from /proc (kB).
int64_t PeakRssKb(Child& server) {
  std::ifstream status("/proc/" + std::to_string(server.pid()) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6));
  }
  return -1;
}

class RogueWorkerTest : public WorkerTest, public ::testing::WithParamInterface<Lie> {};

TEST_P(RogueWorkerTest, LyingBlockIsDroppedTheWorkerBannedAndBIsBitIdentical) {
  // One slow server thread: the rogue, connected first, gets a lease before the job is done.
  StartServer({"--testing-block-delay-ms", "50"});
  FakeWorker rogue(address_, testing::kWorkerToken);
  v1::ServerMessage message;
  ASSERT_TRUE(rogue.Read(&message));
  ASSERT_TRUE(message.has_welcome());
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  ASSERT_TRUE(rogue.Read(&message));
  ASSERT_TRUE(message.has_lease());
  const v1::BlockLease lease = message.lease();
  ASSERT_TRUE(rogue.Send(Forge(lease, GetParam())));

  ExpectSucceedsBitIdentical(job_id, options);
  const std::string log = server_->Log();
  EXPECT_NE(log.find("row block " + std::to_string(lease.block_index()) +
                     " from worker 1 (rogue) rejected, the worker is banned from the job"),
            std::string::npos)
      << log;
  const nlohmann::json workers = Report(*this, job_id)["workers"];
  EXPECT_EQ(workers["rejected_blocks"], 1) << workers.dump(2);
  EXPECT_EQ(workers["remote_rows"], 0) << "nothing of the rogue's was kept";
  // A bomb is refused by its declared size: nothing near 2 GiB is ever allocated.
  EXPECT_LT(PeakRssKb(*server_), 512 << 10);
}

std::string LieName(const ::testing::TestParamInfo<Lie>& lie) {
  static const char* const kNames[] = {"NaN", "BackwardOffsets", "MadeUpRows", "ZstdBomb"};
  return kNames[static_cast<int>(lie.param)];
}

INSTANTIATE_TEST_SUITE_P(Lies, RogueWorkerTest,
                         ::testing::Values(Lie::kNaN, Lie::kBackwardOffsets, Lie::kMadeUpRows,
                                           Lie::kZstdBomb),
                         LieName);

// An honest worker's blocks pass the verification (each recomputed row equals its own) and
// are kept: the report counts them, and rejects none.
TEST_F(WorkerTest, HonestWorkerRowsAreVerifiedAndKept) {
  StartServer({"--testing-block-delay-ms", "100", "--verify-fraction", "0.25"});
  StartWorker({}).WaitForLog("registered with");
  const v1::SolveOptions options = Options();
  const std::string job_id = Submit(options);
  ExpectSucceedsBitIdentical(job_id, options);
  const nlohmann::json workers = Report(*this, job_id)["workers"];
  EXPECT_EQ(workers["rejected_blocks"], 0) << workers.dump(2);
  const int64_t remote = workers["remote_rows"];
  EXPECT_GT(remote, 0) << "the worker built blocks:\n" << server_->Log();
  // 16-row blocks, a quarter of each: 4 rows of every 16 (the last block may be shorter).
  EXPECT_GE(workers["verified_rows"].get<int64_t>(), remote / 4 - 4) << workers.dump(2);
}

// With no worker token the server refuses workers, and tells them the flag that lets them
// in; --allow-workers-without-token does.
TEST_F(WorkerTest, WorkersNeedAWorkerTokenUnlessTheServerAllowsNone) {
  StartServer({"--worker-token", ""});
  Child& refused = StartWorker({"--worker-token", ""});
  EXPECT_EQ(refused.WaitForLog("refused this worker|registered with")[0], "refused this worker");
  const int status = refused.Wait();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << refused.Log();
  EXPECT_NE(refused.Log().find("--allow-workers-without-token"), std::string::npos)
      << refused.Log();

  // A server with a worker token tells a worker without one which flag it lacks.
  StartServer({});
  Child& tokenless = StartWorker({"--worker-token", ""});
  EXPECT_EQ(tokenless.WaitForLog("refused this worker|registered with")[0], "refused this worker");
  EXPECT_TRUE(WIFEXITED(tokenless.Wait())) << tokenless.Log();
  EXPECT_NE(tokenless.Log().find("needs the token of its --worker-token"), std::string::npos)
      << tokenless.Log();

  StartServer({"--allow-workers-without-token"});
  StartWorker({"--worker-token", ""}).WaitForLog("registered with");
}

}  // namespace
}  // namespace radflux
