// Near-field cuts (solver/formfactor/near_field_cuts.h): a quad close to an emitter against its
// size is cut across the emitter's light, not along it, and where the emitter's outline lies
// over it; far, blocked, triangular or emitting faces are left alone; and the grouped mesh
// takes the cuts.
#include "solver/formfactor/near_field_cuts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

QuadCutsByFace Cuts(const Scene& scene) {
  absl::StatusOr<QuadCutsByFace> cuts = NearFieldCuts(scene);
  EXPECT_TRUE(cuts.ok()) << cuts.status();
  return cuts.ok() ? *cuts : QuadCutsByFace{};
}

TEST(NearFieldCuts, HousingTopIsCutAcrossItsTubeAndAtItsEnds) {
  int next = 1;
  const Scene scene = SceneFromObj(TubeAndPlate(0.018, next));
  const QuadCutsByFace cuts = Cuts(scene);
  EXPECT_EQ(cuts.count(0), 0u);  // the emitter
  ASSERT_EQ(cuts.count(1), 1u);
  const QuadCuts& plate = cuts.at(1);
  // Across: the irradiance falls from F = 0.74 above the tube to 0.11 at the plate's edges
  // (Hottel's strips: (sin a2 - sin a1) / 2): 4-8 equal steps.
  ASSERT_GE(plate.u.size(), 3u);
  ASSERT_LE(plate.u.size(), 7u);
  const double step = 1.0 / static_cast<double>(plate.u.size() + 1);
  for (size_t k = 0; k < plate.u.size(); ++k) EXPECT_NEAR(plate.u[k], (k + 1) * step, 1e-12);
  // Along: flat but for the 5 cm beyond each end of the tube, cut off at its ends.
  ASSERT_EQ(plate.v.size(), 2u);
  EXPECT_NEAR(plate.v[0], 0.05 / 1.4, 1e-9);
  EXPECT_NEAR(plate.v[1], 1.35 / 1.4, 1e-9);
}

TEST(NearFieldCuts, FarPlateIsLeftAlone) {
  int next = 1;
  const Scene scene = SceneFromObj(TubeAndPlate(1.0, next));  // F below kNearFieldMinPeak
  EXPECT_EQ(Cuts(scene).count(1), 0u);
}

TEST(NearFieldCuts, PlateBehindABlockerIsLeftAlone) {
  int next = 1;
  std::string obj = TubeAndPlate(0.03, next);
  // A wider opaque sheet between them, 1 cm over the tube, facing it (face 2). Unblocked, the
  // plate would be cut as above.
  obj +=
      ObjQuad("sheet", "white",
              {{-0.1, -0.1, 0.01}, {-0.1, 0.1, 0.01}, {1.5, 0.1, 0.01}, {1.5, -0.1, 0.01}}, next);
  const QuadCutsByFace cuts = Cuts(SceneFromObj(obj));
  EXPECT_EQ(cuts.count(1), 0u);
  EXPECT_EQ(cuts.count(2), 1u);  // the sheet itself is in the tube's near field
}

TEST(NearFieldCuts, TrianglesAndUnlitScenesKeepOneStep) {
  int next = 1;
  std::string obj = TubeAndPlate(0.018, next);
  obj += "o tri\nusemtl white\nv 0 -0.04 0.02\nv 1.4 -0.04 0.02\nv 0.7 0.04 0.02\nf " +
         std::to_string(next) + " " + std::to_string(next + 1) + " " + std::to_string(next + 2) +
         "\n";
  EXPECT_EQ(Cuts(SceneFromObj(obj)).count(2), 0u);
  int none = 1;
  const Scene dark =
      SceneFromObj(ObjQuad("plate", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, none));
  EXPECT_TRUE(Cuts(dark).empty());
}

TEST(NearFieldCuts, GroupedMeshCutsTheHousingTopIntoStrips) {
  // The tube and plate among many small far faces, so that the faces are grouped: the plate's
  // patches are strips along the tube, at most a quarter of its width across, and none
  // straddles an end of the tube.
  int next = 1;
  std::string obj = TubeAndPlate(0.018, next);
  obj += testing::QuadGrid("floor", "white", {-2, -2, -3}, {4, 0, 0}, {0, 4, 0}, 20, next);
  const Scene scene = SceneFromObj(obj);
  MeshOptions options;
  options.target_patches = 100;
  ASSERT_TRUE(GroupsFaces(scene, options));
  absl::StatusOr<PatchMesh> mesh = SubdivideForGrouping(scene, options, Cuts(scene));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  for (uint32_t p = mesh->face_first_patch[1]; p < mesh->face_first_patch[2]; ++p) {
    double lo = 1, hi = -1, x_lo = 2, x_hi = -1;
    for (int k = 0; k < 4; ++k) {
      lo = std::min(lo, mesh->Vertex(p, k).y);
      hi = std::max(hi, mesh->Vertex(p, k).y);
      x_lo = std::min(x_lo, mesh->Vertex(p, k).x);
      x_hi = std::max(x_hi, mesh->Vertex(p, k).x);
    }
    EXPECT_LE(hi - lo, 0.02 + 1e-9) << "patch " << p;
    for (double end : {0.05, 1.35}) EXPECT_FALSE(x_lo < end - 1e-9 && x_hi > end + 1e-9) << p;
  }
}

}  // namespace
}  // namespace radflux
