#include "wire/stored_scene.h"

#include "absl/strings/str_cat.h"
#include "solver/scene/mesh_scene.h"
#include "solver/scene/obj_loader.h"
#include "wire/scene_hash.h"

namespace radflux {
namespace {

Rgb RgbFromProto(const v1::Rgb& rgb) { return {rgb.red(), rgb.green(), rgb.blue()}; }

MeshInput MeshInputFromProto(const v1::Mesh& mesh) {
  MeshInput input;
  input.positions.assign(mesh.positions().begin(), mesh.positions().end());
  input.faces.reserve(mesh.faces_size());
  for (const v1::MeshFace& f : mesh.faces()) {
    MeshFaceInput& face = input.faces.emplace_back();
    face.vertices.assign(f.vertices().begin(), f.vertices().end());
    face.material = f.material();
    face.object = f.object();
    face.group = f.group();
  }
  for (const v1::MeshMaterial& m : mesh.materials()) {
    input.materials.push_back(
        {m.name(), RgbFromProto(m.reflectance()), RgbFromProto(m.emitted_radiance())});
  }
  return input;
}

}  // namespace

std::string StoredSceneHash(const StoredScene& scene) {
  return scene.mesh.empty() ? SceneContentHash(scene.obj, scene.mtl) : MeshContentHash(scene.mesh);
}

absl::StatusOr<Scene> LoadStoredScene(const StoredScene& scene) {
  if (scene.mesh.empty()) return LoadObjText(scene.obj, scene.mtl, scene.name);
  v1::Mesh mesh;
  if (!mesh.ParseFromString(scene.mesh)) {
    return absl::InvalidArgumentError(absl::StrCat(scene.name,
                                                   ": not a serialized radflux.v1.Mesh (",
                                                   scene.mesh.size(), " bytes that do not parse)"));
  }
  return SceneFromMesh(MeshInputFromProto(mesh), scene.name);
}

std::vector<v1::SceneChunk> ToSceneChunks(const StoredScene& scene, const std::string& sha256) {
  constexpr size_t kChunkBytes = 1 << 20;
  std::vector<v1::SceneChunk> chunks(1);
  v1::SceneHeader* header = chunks[0].mutable_header();
  header->set_name(scene.name);
  header->set_obj_size(scene.obj.size());
  header->set_mtl_size(scene.mtl.size());
  header->set_mesh_size(scene.mesh.size());
  header->set_sha256(sha256);
  const std::string data = scene.obj + scene.mtl + scene.mesh;
  for (size_t at = 0; at < data.size(); at += kChunkBytes) {
    chunks.emplace_back().set_data(data.substr(at, kChunkBytes));
  }
  return chunks;
}

absl::StatusOr<uint64_t> ScenePayloadSize(const v1::SceneHeader& header) {
  uint64_t texts = 0;
  uint64_t total = 0;
  if (__builtin_add_overflow(header.obj_size(), header.mtl_size(), &texts) ||
      __builtin_add_overflow(texts, header.mesh_size(), &total)) {
    return absl::InvalidArgumentError(
        absl::StrCat("a scene header's sizes overflow 64 bits (obj_size ", header.obj_size(),
                     ", mtl_size ", header.mtl_size(), ", mesh_size ", header.mesh_size(), ")"));
  }
  if (header.mesh_size() > 0 && texts > 0) {
    return absl::InvalidArgumentError(
        "a scene header declares obj_size/mtl_size (OBJ + MTL text) or mesh_size "
        "(a serialized Mesh), not both");
  }
  return total;
}

absl::StatusOr<StoredScene> SplitScenePayload(const v1::SceneHeader& header,
                                              const std::string& data) {
  const absl::StatusOr<uint64_t> size = ScenePayloadSize(header);
  if (!size.ok()) return absl::DataLossError(size.status().message());
  if (data.size() != *size) {
    return absl::DataLossError(absl::StrCat("scene payload of ", data.size(),
                                            " bytes, its header declares ", *size));
  }
  StoredScene scene;
  scene.name = header.name();
  scene.obj = data.substr(0, header.obj_size());
  scene.mtl = data.substr(header.obj_size(), header.mtl_size());
  scene.mesh = data.substr(header.obj_size() + header.mtl_size());
  return scene;
}

}  // namespace radflux
