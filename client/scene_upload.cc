#include "client/scene_upload.h"

#include <filesystem>

#include "wire/stored_scene.h"

namespace radflux::cli {
namespace {

grpc::Status UploadScene(Client& client, const SceneFile& scene) {
  v1::SceneRef ref;
  auto context = client.Context();
  auto writer = client.stub().UploadScene(context.get(), &ref);
  StoredScene stored;
  stored.name = scene.name;
  stored.files = scene.files;
  for (const v1::SceneChunk& chunk : ToSceneChunks(stored, scene.sha256)) {
    if (!writer->Write(chunk)) break;
  }
  writer->WritesDone();
  return writer->Finish();
}

}  // namespace

absl::StatusOr<SceneFile> ReadSceneFile(const std::string& path) {
  absl::StatusOr<std::vector<BundleFile>> files = ReadSceneBundle(path);
  if (!files.ok()) return files.status();
  SceneFile scene;
  scene.name = std::filesystem::path(path).filename().string();
  scene.files = *std::move(files);
  scene.sha256 = BundleContentHash(scene.files);
  return scene;
}

grpc::Status SubmitScene(Client& client, const SceneFile& scene, v1::SubmitJobRequest& request,
                         v1::Job* job) {
  request.set_scene_sha256(scene.sha256);
  grpc::Status status = client.stub().SubmitJob(client.Context().get(), request, job);
  if (status.error_code() != grpc::StatusCode::NOT_FOUND) return status;
  if (status = UploadScene(client, scene); !status.ok()) return status;
  return client.stub().SubmitJob(client.Context().get(), request, job);
}

}  // namespace radflux::cli
