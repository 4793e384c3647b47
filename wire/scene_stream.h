// The client side of a scene download: the SceneChunk stream of Radiosity.GetScene (the
// client) and of Worker.FetchScene (worker nodes) read back into the scene it carries.
#pragma once

#include <grpcpp/support/sync_stream.h>

#include <string>

#include "absl/status/statusor.h"
#include "radflux/v1/scene.pb.h"
#include "wire/stored_scene.h"

namespace radflux {

// Reads `reader` to its end: the header's name, then OBJ, MTL or Mesh by its sizes.
// The call's own error when it failed; DATA_LOSS when the bytes are not as many as the
// header declares or do not hash (SceneContentHash) to `sha256`.
absl::StatusOr<StoredScene> ReadSceneChunks(grpc::ClientReaderInterface<v1::SceneChunk>& reader,
                                            const std::string& sha256);

}  // namespace radflux
