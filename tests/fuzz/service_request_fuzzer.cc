// libFuzzer target: bytes as what a client or a worker sends radfluxd, structured by the
// .proto: the first byte picks the message, the rest is parsed as it (libFuzzer learns the
// wire format from the seeds in tests/data/service_fuzz_corpus), then converted and checked
// exactly as the server does before any work. Every path must end in OK or a Status, never
// a crash, a sanitizer report or an allocation beyond the declared bounds; conversions
// that succeed must round-trip.
#include <cstddef>
#include <cstdint>
#include <string>

#include <google/protobuf/stubs/logging.h>

#include "radflux/v1/radiosity.pb.h"
#include "radflux/v1/worker.pb.h"
#include "server/store/stored_codec.h"
#include "server/workers/block_wire.h"
#include "server/workers/row_check.h"
#include "solver/pipeline.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

constexpr uint32_t kPatches = 64;  // the leased job's mesh, as the row checks see it

// SubmitJob: the options converted and validated (JobManager::CheckLimits), and a valid
// conversion converts back to the same options.
void Submit(const std::string& bytes) {
  v1::SubmitJobRequest request;
  if (!request.ParseFromString(bytes)) return;
  absl::StatusOr<JobOptions> options = FromProto(request.options());
  if (!options.ok() || !ValidateJobOptions(*options).ok()) return;
  absl::StatusOr<JobOptions> again = FromProto(ToProto(*options));
  if (!again.ok() || ToProto(*again).SerializeAsString() != ToProto(*options).SerializeAsString()) {
    __builtin_trap();
  }
}

// UploadScene: the header's sizes (overflow-checked) and the payload split as declared.
void Upload(const std::string& bytes) {
  v1::SceneChunk chunk;
  if (!chunk.ParseFromString(bytes)) return;
  absl::StatusOr<uint64_t> size = ScenePayloadSize(chunk.header());
  if (!size.ok() || *size != chunk.data().size()) return;
  absl::StatusOr<StoredScene> scene = SplitScenePayload(chunk.header(), chunk.data());
  if (scene.ok() && scene->obj.size() + scene->mtl.size() + scene->mesh.size() > *size) {
    __builtin_trap();
  }
}

// A lease over a kPatches-patch job, from any two numbers.
struct Lease {
  uint32_t first = 0, count = 1;
};
Lease LeaseOf(uint32_t first_row, uint32_t row_count) {
  const uint32_t first = first_row % kPatches;
  return {first, row_count % (kPatches - first) + 1};
}

// A worker's message: a result unpacked within its lease's bound, then its rows checked as
// RowFarm::CheckResult does.
void Worker(const std::string& bytes) {
  v1::WorkerMessage message;
  if (!message.ParseFromString(bytes) || !message.has_result()) return;
  const v1::BlockResult& r = message.result();
  const Lease lease = LeaseOf(r.first_row(), r.row_count());
  absl::StatusOr<StoredRowBlock> rows = UnpackRowBlock(r, MaxRowBlockBytes(lease.count, kPatches));
  if (rows.ok()) (void)CheckRowBlock(rows->block, lease.first, lease.count, kPatches);
}

// A row block's encoding as a liar would send it (with a correct checksum, which the fuzzer
// cannot forge): decoded, then checked in full. Two bytes of lease first.
void RowBlockBytes(const std::string& bytes) {
  if (bytes.size() < 2) return;
  const Lease lease = LeaseOf(static_cast<uint8_t>(bytes[0]), static_cast<uint8_t>(bytes[1]));
  absl::StatusOr<StoredRowBlock> rows = DecodeRowBlock(std::string_view(bytes).substr(2));
  if (rows.ok()) (void)CheckRowBlock(rows->block, lease.first, lease.count, kPatches);
}

}  // namespace
}  // namespace radflux

// Protobuf's log lines (invalid UTF-8 in a string field, as radfluxd's parse refuses it)
// would cost more than the parse itself.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  switch (data[0] % 4) {
    case 0: radflux::Submit(bytes); break;
    case 1: radflux::Upload(bytes); break;
    case 2: radflux::Worker(bytes); break;
    default: radflux::RowBlockBytes(bytes); break;
  }
  return 0;
}
