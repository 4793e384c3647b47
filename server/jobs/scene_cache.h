// SceneCache: the solver Scenes of the most recently used stored scenes, by content
// address and import options. A stored scene never changes under its address, so a cached
// Scene is the one LoadStoredScene would return now; SubmitJob's limits check and the job's start
// then read, verify and parse a scene once instead of twice per job, and not at all for a scene the
// server solved just before (warm state that `radflux solve` pays in every process).
// Holds at most `capacity` scenes. Thread-safe.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "absl/status/statusor.h"
#include "radflux/v1/job.pb.h"
#include "server/jobs/recent_map.h"
#include "server/store/job_store.h"
#include "solver/grouped_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

// A stored scene as loaded: its upload name and its solver Scene, and the unknowns of
// meshing it, each counted once (SubmitJob's limits check and the job's start both need
// it; counting is meshing: ~1 ms for the Cornell box at 8,500 patches, ~2 CPU-s for the
// conference room's probe and grouping).
struct LoadedScene {
  std::string name;
  Scene scene;

  // The number of unknowns of SubdivideAndGroup(scene, options) (patches, or groups of
  // them), 0 when it fails. Thread-safe.
  uint64_t PatchCount(const MeshOptions& options) const;

  // The mesh the latest PatchCount that meshed built, when it was for `options` and is not
  // taken yet: the job it was counted for takes it instead of meshing again (PrepareJob).
  // One mesh at most is held (the latest count's), until taken or the scene leaves the
  // cache. Thread-safe.
  std::optional<GroupedMesh> TakeMesh(const MeshOptions& options) const;

 private:
  using Key = std::tuple<int64_t, double, bool, bool, double>;  // MeshOptions' fields
  static Key KeyOf(const MeshOptions& options);

  mutable std::mutex mu_;  // guards counts_ and mesh_
  mutable std::map<Key, uint64_t> counts_;
  mutable std::optional<std::pair<Key, GroupedMesh>> mesh_;
};

class SceneCache {
 public:
  explicit SceneCache(JobStore& store, size_t capacity = 2) : store_(store), recent_(capacity) {}

  // The scene stored under `sha256` read with the import rules `import`, as LoadStoredScene
  // returns it, and validated (ValidateScene, an emitter required): NOT_FOUND when no scene
  // has that address, INVALID_ARGUMENT when it does not load or is not valid (the loader's,
  // the rules' or the validation's message).
  absl::StatusOr<std::shared_ptr<const LoadedScene>> Get(const std::string& sha256,
                                                         const v1::ImportOptions& import);

 private:
  JobStore& store_;
  RecentMap<LoadedScene> recent_;
};

}  // namespace radflux
