#include "wire/scene_stream.h"

#include "absl/strings/str_cat.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {

absl::StatusOr<StoredScene> ReadSceneChunks(grpc::ClientReaderInterface<v1::SceneChunk>& reader,
                                            const std::string& sha256) {
  v1::SceneChunk chunk;
  v1::SceneHeader header;
  std::string data;
  while (reader.Read(&chunk)) {
    if (chunk.has_header()) header = chunk.header();
    data += chunk.data();
  }
  if (absl::Status s = FromGrpcStatus(reader.Finish()); !s.ok()) return s;
  absl::StatusOr<StoredScene> scene = SplitScenePayload(header, data);
  if (!scene.ok()) {
    return absl::DataLossError(absl::StrCat("scene ", sha256, ": ", scene.status().message()));
  }
  if (StoredSceneHash(*scene) != sha256) {
    return absl::DataLossError("scene " + sha256 + " does not hash to its address");
  }
  return scene;
}

}  // namespace radflux
