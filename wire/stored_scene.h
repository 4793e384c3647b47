// A stored scene in either upload form (OBJ + MTL texts, or a serialized v1::Mesh): its
// content address, its solver Scene and the SceneChunk stream that carries it. The one
// place that knows both forms, used by the server, worker nodes and the client alike.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/scene.pb.h"
#include "solver/scene/scene.h"

namespace radflux {

// An uploaded scene as it was uploaded: OBJ and MTL texts, or a serialized v1::Mesh (then
// obj and mtl are empty).
struct StoredScene {
  std::string name;
  std::string obj;
  std::string mtl;
  std::string mesh;
};

// SceneContentHash of the texts, or MeshContentHash of the mesh bytes.
std::string StoredSceneHash(const StoredScene& scene);

// The scene as the solver sees it (not yet validated: see ValidateScene); INVALID_ARGUMENT
// with the loader's message (for a Mesh: the face index and what is wrong).
absl::StatusOr<Scene> LoadStoredScene(const StoredScene& scene);

// The SceneChunk stream of GetScene / FetchScene: the header (name, sizes, `sha256`),
// then data chunks of at most 1 MiB whose concatenation is obj + mtl, or the mesh.
std::vector<v1::SceneChunk> ToSceneChunks(const StoredScene& scene, const std::string& sha256);

// The payload size a header declares: obj_size + mtl_size + mesh_size. INVALID_ARGUMENT when
// the sum overflows 64 bits or the header declares both forms (OBJ + MTL texts and a Mesh).
absl::StatusOr<uint64_t> ScenePayloadSize(const v1::SceneHeader& header);

// The payload of an upload or download split by its header's sizes; DATA_LOSS (never an
// exception) when data.size() is not their sum or the sizes are not valid (ScenePayloadSize).
absl::StatusOr<StoredScene> SplitScenePayload(const v1::SceneHeader& header,
                                              const std::string& data);

}  // namespace radflux
