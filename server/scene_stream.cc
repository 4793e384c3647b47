#include "server/scene_stream.h"

#include "absl/strings/str_cat.h"
#include "server/proto_convert.h"
#include "server/scene_hash.h"

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
  if (data.size() != header.obj_size() + header.mtl_size()) {
    return absl::DataLossError(absl::StrCat("scene ", sha256, ": got ", data.size(),
                                            " bytes, expected ",
                                            header.obj_size() + header.mtl_size()));
  }
  StoredScene scene{header.name(), data.substr(0, header.obj_size()),
                    data.substr(header.obj_size())};
  if (SceneContentHash(scene.obj, scene.mtl) != sha256) {
    return absl::DataLossError("scene " + sha256 + " does not hash to its address");
  }
  return scene;
}

}  // namespace radflux
