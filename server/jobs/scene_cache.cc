#include "server/jobs/scene_cache.h"

#include "solver/scene/validation.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {

LoadedScene::Key LoadedScene::KeyOf(const MeshOptions& options) {
  return {options.target_patches, options.max_edge, options.group_faces, options.follow_contacts,
          options.min_contact_area};
}

uint64_t LoadedScene::PatchCount(const MeshOptions& options) const {
  const Key key = KeyOf(options);
  {
    std::lock_guard lock(mu_);
    if (auto it = counts_.find(key); it != counts_.end()) return it->second;
  }
  absl::StatusOr<GroupedMesh> mesh = SubdivideAndGroup(scene, options);
  const uint64_t count =
      !mesh.ok() ? 0 : (mesh->clusters.empty() ? mesh->mesh.size() : mesh->clusters.size());
  std::lock_guard lock(mu_);
  counts_.emplace(key, count);
  if (mesh.ok()) mesh_.emplace(key, *std::move(mesh));
  return count;
}

std::optional<GroupedMesh> LoadedScene::TakeMesh(const MeshOptions& options) const {
  std::lock_guard lock(mu_);
  if (!mesh_.has_value() || mesh_->first != KeyOf(options)) return std::nullopt;
  std::optional<GroupedMesh> taken(std::move(mesh_->second));
  mesh_.reset();
  return taken;
}

absl::StatusOr<std::shared_ptr<const LoadedScene>> SceneCache::Get(
    const std::string& sha256, const v1::ImportOptions& import) {
  const std::string key = sha256 + "\n" + import.SerializeAsString();
  if (std::shared_ptr<const LoadedScene> cached = recent_.Get(key)) return cached;
  absl::StatusOr<ImportOptions> options = FromProto(import);
  if (!options.ok()) return options.status();
  absl::StatusOr<StoredScene> stored = store_.GetScene(sha256);
  if (!stored.ok()) return stored.status();
  const std::string name = stored->name;
  absl::StatusOr<Scene> loaded = LoadStoredScene(*std::move(stored), *options);
  if (!loaded.ok()) return absl::InvalidArgumentError(std::string(loaded.status().message()));
  if (absl::Status s = ValidateScene(*loaded); !s.ok()) {
    return absl::InvalidArgumentError(std::string(s.message()));
  }
  auto scene = std::make_shared<LoadedScene>();
  scene->name = name;
  scene->scene = *std::move(loaded);
  recent_.Put(key, scene);
  return scene;
}

}  // namespace radflux
