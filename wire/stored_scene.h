// A stored scene in any upload form (a bundle of files, OBJ + MTL texts, or a serialized
// v1::Mesh): its content address, its solver Scene and the SceneChunk stream that carries
// it. The one place that knows all forms, used by the server, worker nodes and the client.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/scene.pb.h"
#include "solver/scene/import_options.h"
#include "solver/scene/load_scene.h"
#include "solver/scene/scene.h"
#include "wire/scene_bundle.h"

namespace radflux {

// An uploaded scene as it was uploaded: a bundle of files (the scene file first), OBJ and
// MTL texts, or a serialized v1::Mesh; the other forms' fields are empty.
struct StoredScene {
  std::string name;
  std::string obj;
  std::string mtl;
  std::string mesh;
  std::vector<BundleFile> files;
};

// BundleContentHash of the files, SceneContentHash of the texts, or MeshContentHash of the
// mesh bytes.
std::string StoredSceneHash(const StoredScene& scene);

// The scene as the solver sees it, read with the import rules `options` as `radflux solve`
// reads it (a bundle through LoadSceneBundle; OBJ text and Mesh through their loaders, then
// ApplyImportRules). Not yet validated: see ValidateScene. INVALID_ARGUMENT with the
// loader's or the rules' message (for a Mesh: the face index and what is wrong). Takes the
// scene by value: a bundle's bytes are moved, not copied, into the loader's files.
absl::StatusOr<Scene> LoadStoredScene(StoredScene scene, const ImportOptions& options);

// The bundle of a stored scene of bundle form (files not empty), its files' bytes moved.
SceneBundle TakeSceneBundle(StoredScene& scene);

// The SceneChunk stream of GetScene / FetchScene: the header (name, sizes or the bundle's
// files, `sha256`), then data chunks of at most 1 MiB whose concatenation is obj + mtl, the
// mesh, or the bundle's files in order.
std::vector<v1::SceneChunk> ToSceneChunks(const StoredScene& scene, const std::string& sha256);

// Most files a bundle may have.
inline constexpr int kMaxBundleFiles = 10000;

// The payload size a header declares: obj_size + mtl_size + mesh_size + the bundle files'
// sizes. INVALID_ARGUMENT when the sum overflows 64 bits, the header declares more than one
// form, a bundle has more than kMaxBundleFiles files, or a bundle path is not allowed
// (CheckBundlePaths: absolute, '..', repeated; the message names the path).
absl::StatusOr<uint64_t> ScenePayloadSize(const v1::SceneHeader& header);

// The payload of an upload or download split by its header's sizes; DATA_LOSS (never an
// exception) when data.size() is not their sum or the sizes are not valid (ScenePayloadSize).
absl::StatusOr<StoredScene> SplitScenePayload(const v1::SceneHeader& header,
                                              const std::string& data);

}  // namespace radflux
