// Recentring (issue 19): a room far from the origin (x = 100 km, as CAD and GIS exports
// put it) is moved near the origin in double before anything becomes float, so it solves
// to the same B as the same room at the origin, and outputs get the file's coordinates back.
#include <gtest/gtest.h>

#include "solver/mesh/patch_mesh.h"
#include "solver/pipeline.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/mesh_scene.h"
#include "solver/scene/recentre.h"

namespace radflux {
namespace {

// A closed 4 x 3 x 2.5 room (faces inward) with a lamp patch on the ceiling, moved by x0.
Scene Room(double x0) {
  MeshInput mesh;
  mesh.materials = {{"wall", Rgb{0.7, 0.5, 0.3}, {}}, {"lamp", Rgb{0.2, 0.2, 0.2}, Rgb{5, 5, 5}}};
  auto quad = [&](std::array<Vec3, 4> corners, uint32_t material) {
    MeshFaceInput face;
    for (const Vec3& c : corners) {
      face.vertices.push_back(static_cast<uint32_t>(mesh.positions.size() / 3));
      mesh.positions.insert(mesh.positions.end(), {c.x + x0, c.y, c.z});
    }
    face.material = material;
    mesh.faces.push_back(face);
  };
  const double X = 4, Y = 3, Z = 2.5;
  quad({Vec3{0, 0, 0}, {X, 0, 0}, {X, Y, 0}, {0, Y, 0}}, 0);  // floor, facing +z
  quad({Vec3{0, 0, Z}, {0, Y, Z}, {X, Y, Z}, {X, 0, Z}}, 0);  // ceiling, facing -z
  quad({Vec3{0, 0, 0}, {0, Y, 0}, {0, Y, Z}, {0, 0, Z}}, 0);  // x = 0, facing +x
  quad({Vec3{X, 0, 0}, {X, 0, Z}, {X, Y, Z}, {X, Y, 0}}, 0);  // x = X, facing -x
  quad({Vec3{0, 0, 0}, {0, 0, Z}, {X, 0, Z}, {X, 0, 0}}, 0);  // y = 0, facing +y
  quad({Vec3{0, Y, 0}, {X, Y, 0}, {X, Y, Z}, {0, Y, Z}}, 0);  // y = Y, facing -y
  quad({Vec3{1.5, 1, 2.25}, {1.5, 2, 2.25}, {2.5, 2, 2.25}, {2.5, 1, 2.25}}, 1);  // lamp
  absl::StatusOr<Scene> scene = SceneFromMesh(mesh, "room");
  EXPECT_TRUE(scene.ok()) << scene.status();
  EXPECT_TRUE(ApplyImportRules(ImportOptions{}, *scene).ok());
  return *std::move(scene);
}

JobResult Solve(Scene scene) {
  JobOptions options;
  options.mesh.max_edge = 0.5;
  options.form_factors.rays = 256;
  options.form_factors.threads = 2;
  options.solver.tolerance = 1e-6;
  absl::StatusOr<JobResult> result = RunJob(std::move(scene), options);
  EXPECT_TRUE(result.ok()) << result.status();
  return *std::move(result);
}

TEST(Recentre, OffsetIsZeroNearTheOriginAndExactFarFromIt) {
  EXPECT_EQ(RecentringOffset({0, 0, 0}, {556, 548.8, 559.2}), Vec3{});  // the Cornell box
  EXPECT_EQ(RecentringOffset({-10, -10, -10}, {10, 10, 10}), Vec3{});
  // A 4 x 3 x 2.5 room at x = 100 km: q = 32 >= 4 x diagonal, and 100000 = 3125 x 32.
  EXPECT_EQ(RecentringOffset({1e5, 0, 0}, {1e5 + 4, 3, 2.5}), (Vec3{1e5, 0, 0}));
}

TEST(Recentre, ARoomAtOneHundredKilometresSolvesToTheSameRadiosityAsAtTheOrigin) {
  const Scene near = Room(0), far = Room(1e5);
  EXPECT_EQ(near.origin, Vec3{});
  EXPECT_EQ(far.origin, (Vec3{1e5, 0, 0}));
  EXPECT_EQ(far.positions, near.positions);  // the subtraction is exact (Sterbenz)
  ASSERT_EQ(far.import_log.fixups().size(), 1u);
  EXPECT_EQ(far.import_log.fixups()[0].kind, "recentred");
  const JobResult a = Solve(near), b = Solve(far);
  ASSERT_EQ(a.solve.radiosity.size(), b.solve.radiosity.size());
  for (size_t p = 0; p < a.solve.radiosity.size(); ++p) {
    EXPECT_EQ(a.solve.radiosity[p], b.solve.radiosity[p]) << "patch " << p;  // bit-identical
  }
  // Outputs put the mesh back where the file had it.
  const PatchMesh out = TranslatedMesh(b.job->mesh, b.job->scene.origin);
  EXPECT_EQ(out.positions[0], (Vec3{1e5, 0, 0}));
  EXPECT_EQ(out.patches[0].centroid.x, b.job->mesh.patches[0].centroid.x + 1e5);
}

TEST(Recentre, WithoutRecentringTheFarRoomSolvesDifferently) {
  // The test above is not vacuous: the same far room solved where it is (float rays and
  // sample points ~4 mm apart at 100 km) gives another B.
  Scene far = Room(1e5);
  for (Vec3& p : far.positions) p += far.origin;
  far.origin = {};
  const JobResult a = Solve(Room(0)), b = Solve(std::move(far));
  ASSERT_EQ(a.solve.radiosity.size(), b.solve.radiosity.size());
  size_t differ = 0;
  for (size_t p = 0; p < a.solve.radiosity.size(); ++p) differ += a.solve.radiosity[p] != b.solve.radiosity[p];
  EXPECT_GT(differ, a.solve.radiosity.size() / 2);
}

}  // namespace
}  // namespace radflux
