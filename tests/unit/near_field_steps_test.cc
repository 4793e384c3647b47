// Near-field steps (solver/mesh/near_field_steps.h): a quad close to an emitter against its size
// is cut across the emitter's light, not along it; far, blocked, triangular or emitting faces
// are left alone; and the grouped mesh takes the steps.
#include "solver/formfactor/near_field_steps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

#include "solver/mesh/face_grouping.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::SceneFromObj;

// A 1.3 x 0.04 m tube along x at z = 0 facing up (face 0), and a 1.4 x 0.08 m plate above it
// at height `h` facing down (face 1), its vertices 0 -> 1 along y (u: across the tube) and
// 0 -> 3 along x (v: along it): a lamp housing's top over its tube.
std::string TubeAndPlate(double h, int& next) {
  std::string obj = ObjQuad(
      "tube", "lamp", {{0.05, -0.02, 0}, {1.35, -0.02, 0}, {1.35, 0.02, 0}, {0.05, 0.02, 0}}, next);
  obj += ObjQuad("plate", "white", {{0, -0.04, h}, {0, 0.04, h}, {1.4, 0.04, h}, {1.4, -0.04, h}},
                 next);
  return obj;
}

std::vector<std::pair<int, int>> Steps(const Scene& scene) {
  absl::StatusOr<std::vector<std::pair<int, int>>> steps = NearFieldSteps(scene);
  EXPECT_TRUE(steps.ok()) << steps.status();
  return steps.ok() ? *steps : std::vector<std::pair<int, int>>(scene.faces.size(), {0, 0});
}

TEST(NearFieldSteps, HousingTopIsCutAcrossItsTubeNotAlongIt) {
  int next = 1;
  const Scene scene = SceneFromObj(TubeAndPlate(0.018, next));
  const auto steps = Steps(scene);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0], std::make_pair(1, 1));  // the emitter
  // Across: the irradiance falls from F = 0.74 above the tube to 0.11 at the plate's edges
  // (Hottel's strips: (sin a2 - sin a1) / 2); along: flat but for the last few cm.
  EXPECT_GE(steps[1].first, 4);
  EXPECT_LE(steps[1].first, 8);
  EXPECT_EQ(steps[1].second, 1);
}

TEST(NearFieldSteps, FarPlateIsLeftAlone) {
  int next = 1;
  const Scene scene = SceneFromObj(TubeAndPlate(1.0, next));  // F below kNearFieldMinPeak
  EXPECT_EQ(Steps(scene)[1], std::make_pair(1, 1));
}

TEST(NearFieldSteps, PlateBehindABlockerIsLeftAlone) {
  int next = 1;
  std::string obj = TubeAndPlate(0.03, next);
  // A wider opaque sheet between them, 1 cm over the tube, facing it (face 2). Unblocked, the
  // plate would be cut as above.
  obj +=
      ObjQuad("sheet", "white",
              {{-0.1, -0.1, 0.01}, {-0.1, 0.1, 0.01}, {1.5, 0.1, 0.01}, {1.5, -0.1, 0.01}}, next);
  const auto steps = Steps(SceneFromObj(obj));
  EXPECT_EQ(steps[1], std::make_pair(1, 1));
  EXPECT_GT(steps[2].first * steps[2].second, 1);  // the sheet itself is in the tube's near field
}

TEST(NearFieldSteps, TrianglesAndUnlitScenesKeepOneStep) {
  int next = 1;
  std::string obj = TubeAndPlate(0.018, next);
  obj += "o tri\nusemtl white\nv 0 -0.04 0.02\nv 1.4 -0.04 0.02\nv 0.7 0.04 0.02\nf " +
         std::to_string(next) + " " + std::to_string(next + 1) + " " + std::to_string(next + 2) +
         "\n";
  EXPECT_EQ(Steps(SceneFromObj(obj))[2], std::make_pair(1, 1));
  int none = 1;
  const Scene dark =
      SceneFromObj(ObjQuad("plate", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, none));
  EXPECT_EQ(Steps(dark)[0], std::make_pair(1, 1));
}

TEST(NearFieldSteps, GroupedMeshCutsTheHousingTopIntoStrips) {
  // The tube and plate among many small far faces, so that the faces are grouped: the plate's
  // patches are strips along the tube, at most a quarter of its width across.
  int next = 1;
  std::string obj = TubeAndPlate(0.018, next);
  obj += testing::QuadGrid("floor", "white", {-2, -2, -3}, {4, 0, 0}, {0, 4, 0}, 20, next);
  const Scene scene = SceneFromObj(obj);
  MeshOptions options;
  options.target_patches = 100;
  ASSERT_TRUE(GroupsFaces(scene, options));
  absl::StatusOr<PatchMesh> mesh = SubdivideForGrouping(scene, options, Steps(scene));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  for (uint32_t p = mesh->face_first_patch[1]; p < mesh->face_first_patch[2]; ++p) {
    double lo = 1, hi = -1;
    for (int k = 0; k < 4; ++k) {
      lo = std::min(lo, mesh->Vertex(p, k).y);
      hi = std::max(hi, mesh->Vertex(p, k).y);
    }
    EXPECT_LE(hi - lo, 0.02 + 1e-9) << "patch " << p;
  }
}

}  // namespace
}  // namespace radflux
