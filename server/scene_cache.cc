#include "server/scene_cache.h"

#include "server/stored_scene.h"

namespace radflux {

absl::StatusOr<std::shared_ptr<const LoadedScene>> SceneCache::Get(const std::string& sha256) {
  {
    std::lock_guard lock(mu_);
    for (const auto& [address, scene] : recent_) {
      if (address == sha256) return scene;
    }
  }
  absl::StatusOr<StoredScene> stored = store_.GetScene(sha256);
  if (!stored.ok()) return stored.status();
  absl::StatusOr<Scene> loaded = LoadStoredScene(*stored);
  if (!loaded.ok()) return absl::InvalidArgumentError(std::string(loaded.status().message()));
  auto scene = std::make_shared<const LoadedScene>(LoadedScene{stored->name, *std::move(loaded)});
  std::lock_guard lock(mu_);
  recent_.emplace_front(sha256, scene);
  if (recent_.size() > capacity_) recent_.pop_back();
  return scene;
}

}  // namespace radflux
