// LoadedScene (server/jobs/scene_cache.h): a job's unknowns are counted by meshing, and the
// job then takes that mesh instead of meshing again; the mesh is handed out once, only for
// the options it was counted with.
#include "server/jobs/scene_cache.h"

#include <gtest/gtest.h>

#include "solver/scene/obj_loader.h"
#include "tests/integration/test_helpers.h"

namespace radflux {
namespace {

TEST(LoadedScene, TheMeshACountBuiltIsTakenOnceForItsOptions) {
  LoadedScene loaded;
  absl::StatusOr<Scene> scene = LoadObjText(testing::kObj, testing::kMtl, "cornell_box.obj");
  ASSERT_TRUE(scene.ok()) << scene.status();
  loaded.scene = *std::move(scene);
  MeshOptions grouped;
  grouped.target_patches = 8;  // 17 faces: grouped
  MeshOptions other = grouped;
  other.follow_contacts = false;

  const uint64_t count = loaded.PatchCount(grouped);
  EXPECT_FALSE(loaded.TakeMesh(other).has_value()) << "a mesh of other options";
  std::optional<GroupedMesh> taken = loaded.TakeMesh(grouped);
  ASSERT_TRUE(taken.has_value());
  ASSERT_FALSE(taken->clusters.empty());
  EXPECT_EQ(taken->clusters.size(), count);
  EXPECT_NE(taken->caster, nullptr) << "the probe's Embree scene comes with it";
  EXPECT_FALSE(loaded.TakeMesh(grouped).has_value()) << "taken twice";

  EXPECT_EQ(loaded.PatchCount(grouped), count) << "counted once: no mesh is built again";
  EXPECT_FALSE(loaded.TakeMesh(grouped).has_value());
}

}  // namespace
}  // namespace radflux
