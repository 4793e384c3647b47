// Sending a scene to radfluxd: the scene file with the files it names (MTL, textures, glTF
// buffers and images, MGF includes) as one bundle, by content address first.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "client/service_client.h"
#include "wire/scene_bundle.h"

namespace radflux::cli {

// A scene as the client sends it: its bundle (the scene file first) and its content
// address (BundleContentHash).
struct SceneFile {
  std::string name, sha256;
  std::vector<BundleFile> files;
};

// Reads the scene file at `path` and the files it names (ReadSceneBundle).
absl::StatusOr<SceneFile> ReadSceneFile(const std::string& path);

// Submits `request` for `scene`: by its content address first, so that a scene the server
// already holds is not sent again (one call instead of two); uploaded, and submitted again,
// only when the server answers NOT_FOUND.
grpc::Status SubmitScene(Client& client, const SceneFile& scene, v1::SubmitJobRequest& request,
                         v1::Job* job);

}  // namespace radflux::cli
