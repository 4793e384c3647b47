#include "client/scene_upload.h"

#include <filesystem>
#include <sstream>

#include "wire/grpc_credentials.h"
#include "wire/scene_hash.h"

namespace radflux::cli {
namespace {

namespace fs = std::filesystem;

// The MTL text of an OBJ: its mtllib file beside it, else SCENE.mtl, else empty.
std::string FindMtl(const std::string& obj_path, const std::string& obj) {
  std::istringstream lines(obj);
  std::string line, mtl;
  while (std::getline(lines, line)) {
    if (line.rfind("mtllib ", 0) == 0) {
      std::string name = line.substr(7);
      while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
      if (ReadFile((fs::path(obj_path).parent_path() / name).string(), &mtl)) return mtl;
    }
  }
  ReadFile(fs::path(obj_path).replace_extension(".mtl").string(), &mtl);
  return mtl;
}

grpc::Status UploadScene(Client& client, const SceneFile& scene) {
  v1::SceneRef ref;
  auto context = client.Context();
  auto writer = client.stub().UploadScene(context.get(), &ref);
  v1::SceneChunk chunk;
  chunk.mutable_header()->set_name(scene.name);
  chunk.mutable_header()->set_obj_size(scene.obj.size());
  chunk.mutable_header()->set_mtl_size(scene.mtl.size());
  chunk.mutable_header()->set_sha256(scene.sha256);
  const std::string data = scene.obj + scene.mtl;
  constexpr size_t kChunk = 1 << 20;
  for (size_t at = 0; at == 0 || at < data.size(); at += kChunk) {
    chunk.set_data(data.substr(at, kChunk));
    if (!writer->Write(chunk)) break;
    chunk.clear_header();
  }
  writer->WritesDone();
  return writer->Finish();
}

}  // namespace

absl::StatusOr<SceneFile> ReadSceneFile(const std::string& path) {
  SceneFile scene;
  if (!ReadFile(path, &scene.obj)) return absl::NotFoundError("cannot read " + path);
  scene.mtl = FindMtl(path, scene.obj);
  scene.name = fs::path(path).filename().string();
  scene.sha256 = SceneContentHash(scene.obj, scene.mtl);
  return scene;
}

// Submits `request` for `scene`: by its content address first, so that a scene the server
// already holds is not sent again (one call instead of two); uploaded, and submitted again,
// only when the server answers NOT_FOUND.
grpc::Status SubmitScene(Client& client, const SceneFile& scene, v1::SubmitJobRequest& request,
                         v1::Job* job) {
  request.set_scene_sha256(scene.sha256);
  grpc::Status status = client.stub().SubmitJob(client.Context().get(), request, job);
  if (status.error_code() != grpc::StatusCode::NOT_FOUND) return status;
  if (status = UploadScene(client, scene); !status.ok()) return status;
  return client.stub().SubmitJob(client.Context().get(), request, job);
}

}  // namespace radflux::cli
