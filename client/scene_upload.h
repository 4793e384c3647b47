// Sending a scene file to radfluxd: the OBJ with its MTL, by content address first.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "client/service_client.h"

namespace radflux::cli {

// An OBJ scene file as the client sends it: its text, its MTL text and their content address.
struct SceneFile {
  std::string name, obj, mtl, sha256;
};

// Reads the OBJ at `path` and its MTL (its mtllib file beside it, else SCENE.mtl, else none).
absl::StatusOr<SceneFile> ReadSceneFile(const std::string& path);

// Submits `request` for `scene`: by its content address first, so that a scene the server
// already holds is not sent again (one call instead of two); uploaded, and submitted again,
// only when the server answers NOT_FOUND.
grpc::Status SubmitScene(Client& client, const SceneFile& scene, v1::SubmitJobRequest& request,
                         v1::Job* job);

}  // namespace radflux::cli
