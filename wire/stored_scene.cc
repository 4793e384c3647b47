#include "wire/stored_scene.h"

#include <optional>

#include "absl/strings/str_cat.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/load_scene.h"
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
    input.materials.push_back({m.name(), RgbFromProto(m.reflectance()),
                               RgbFromProto(m.emitted_radiance()),
                               m.has_opacity() ? m.opacity() : 1.0});
  }
  return input;
}

// The scene of an OBJ + MTL or Mesh upload as its loader reads it, before the import rules.
absl::StatusOr<Scene> LoadTextOrMesh(const StoredScene& scene) {
  if (scene.mesh.empty()) return LoadObjText(scene.obj, scene.mtl, scene.name);
  v1::Mesh mesh;
  if (!mesh.ParseFromString(scene.mesh)) {
    return absl::InvalidArgumentError(absl::StrCat(scene.name,
                                                   ": not a serialized radflux.v1.Mesh (",
                                                   scene.mesh.size(), " bytes that do not parse)"));
  }
  return SceneFromMesh(MeshInputFromProto(mesh), scene.name);
}

// The bytes a header's sizes add up to, or nullopt when they overflow 64 bits.
std::optional<uint64_t> SumOfSizes(const v1::SceneHeader& header) {
  uint64_t total = 0;
  for (uint64_t size : {header.obj_size(), header.mtl_size(), header.mesh_size()}) {
    if (__builtin_add_overflow(total, size, &total)) return std::nullopt;
  }
  for (const v1::BundleFile& file : header.files()) {
    if (__builtin_add_overflow(total, file.size(), &total)) return std::nullopt;
  }
  return total;
}

absl::Status CheckBundleHeader(const v1::SceneHeader& header) {
  if (header.files_size() > kMaxBundleFiles) {
    return absl::InvalidArgumentError(absl::StrCat("a bundle of ", header.files_size(),
                                                   " files; at most ", kMaxBundleFiles));
  }
  std::vector<std::string> paths;
  for (const v1::BundleFile& file : header.files()) paths.push_back(file.path());
  return CheckBundlePaths(paths);
}

}  // namespace

std::string StoredSceneHash(const StoredScene& scene) {
  if (!scene.files.empty()) return BundleContentHash(scene.files);
  return scene.mesh.empty() ? SceneContentHash(scene.obj, scene.mtl) : MeshContentHash(scene.mesh);
}

SceneBundle TakeSceneBundle(StoredScene& scene) {
  SceneBundle bundle{scene.files[0].path, {}};
  for (BundleFile& file : scene.files) bundle.files.emplace(file.path, std::move(file.data));
  return bundle;
}

absl::StatusOr<Scene> LoadStoredScene(StoredScene scene, const ImportOptions& options) {
  if (!scene.files.empty()) return LoadSceneBundle(TakeSceneBundle(scene), options);
  absl::StatusOr<Scene> loaded = LoadTextOrMesh(scene);
  if (!loaded.ok()) return loaded.status();
  if (absl::Status s = ApplyImportRules(options, *loaded); !s.ok()) return s;
  return loaded;
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
  std::string data = scene.obj + scene.mtl + scene.mesh;
  for (const BundleFile& file : scene.files) {
    v1::BundleFile* entry = header->add_files();
    entry->set_path(file.path);
    entry->set_size(file.data.size());
    data += file.data;
  }
  for (size_t at = 0; at < data.size(); at += kChunkBytes) {
    chunks.emplace_back().set_data(data.substr(at, kChunkBytes));
  }
  return chunks;
}

absl::StatusOr<uint64_t> ScenePayloadSize(const v1::SceneHeader& header) {
  const std::optional<uint64_t> total = SumOfSizes(header);
  if (!total) {
    return absl::InvalidArgumentError(
        absl::StrCat("a scene header's sizes overflow 64 bits (obj_size ", header.obj_size(),
                     ", mtl_size ", header.mtl_size(), ", mesh_size ", header.mesh_size(),
                     ", ", header.files_size(), " bundle files)"));
  }
  const bool texts = header.obj_size() > 0 || header.mtl_size() > 0;
  const bool mesh = header.mesh_size() > 0;
  const bool bundle = header.files_size() > 0;
  if (int{texts} + int{mesh} + int{bundle} > 1) {
    return absl::InvalidArgumentError(
        "a scene header declares more than one form: obj_size/mtl_size (OBJ + MTL text), "
        "mesh_size (a serialized Mesh) or files (a bundle); give one, not both");
  }
  if (bundle) {
    if (absl::Status s = CheckBundleHeader(header); !s.ok()) return s;
  }
  return *total;
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
  scene.mesh = data.substr(header.obj_size() + header.mtl_size(), header.mesh_size());
  uint64_t at = header.obj_size() + header.mtl_size() + header.mesh_size();
  for (const v1::BundleFile& file : header.files()) {
    scene.files.push_back({file.path(), data.substr(at, file.size())});
    at += file.size();
  }
  return scene;
}

}  // namespace radflux
