// Two-sided surfaces (issue 19): a face whose material is two-sided is two back-to-back
// patches, each lit from its own side, and its twin never shades it.
#include <gtest/gtest.h>

#include <numbers>

#include "solver/pipeline.h"
#include "solver/raytrace/brute_force_ray_caster.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/obj_loader.h"

namespace radflux {
namespace {

// A unit panel (grey, rho 0.5) at z = 0 facing +z, between two black unit lamps (L_e 1) at
// z = +1 facing down and z = -1 facing up.
const char* kPanelObj =
    "o top_lamp\nusemtl lamp\nv 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\nf 1 2 3 4\n"
    "o bottom_lamp\nusemtl lamp\nv 0 0 -1\nv 1 0 -1\nv 1 1 -1\nv 0 1 -1\nf 5 6 7 8\n"
    "o panel\nusemtl grey\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 9 10 11 12\n";
const char* kPanelMtl = "newmtl lamp\nKd 0 0 0\nKe 1 1 1\nnewmtl grey\nKd 0.5 0.5 0.5\n";

// Form factor between two parallel coaxial unit squares one unit apart (Howell C-11).
constexpr double kParallelSquares = 0.19982;

// Mean radiosity (band 0) of the patches of face f.
double FaceRadiosity(const JobResult& result, uint32_t f) {
  const PatchMesh& mesh = result.job->mesh;
  double power = 0, area = 0;
  for (uint32_t p = mesh.face_first_patch[f]; p < mesh.face_first_patch[f + 1]; ++p) {
    power += result.solve.radiosity[p][0] * mesh.patches[p].area;
    area += mesh.patches[p].area;
  }
  return power / area;
}

JobResult SolvePanel(bool two_sided) {
  absl::StatusOr<Scene> scene = LoadObjText(kPanelObj, kPanelMtl, "panel.obj");
  EXPECT_TRUE(scene.ok()) << scene.status();
  ImportOptions import;
  import.two_sided = two_sided;
  EXPECT_TRUE(ApplyImportRules(import, *scene).ok());
  JobOptions options;
  options.mesh.max_edge = 0.25;
  options.form_factors.method = FormFactorMethod::kAnalytic;
  options.form_factors.samples = 16;
  options.solver.tolerance = 1e-8;
  absl::StatusOr<JobResult> result = RunJob(*std::move(scene), options);
  EXPECT_TRUE(result.ok()) << result.status();
  return *std::move(result);
}

TEST(TwoSided, APanelLitFromBothSidesIsLitOnEachSideByItsOwnLamp) {
  const JobResult result = SolvePanel(/*two_sided=*/true);
  // Faces: the lamps and the panel (0-2, every material two-sided), then their twins (3-5).
  ASSERT_EQ(result.job->scene.faces.size(), 6u);
  const double expected = 0.5 * std::numbers::pi * kParallelSquares;  // rho * E * F
  const double top = FaceRadiosity(result, 2), bottom = FaceRadiosity(result, 5);
  EXPECT_NEAR(top, expected, 0.01 * expected);
  EXPECT_NEAR(bottom, expected, 0.01 * expected);
  EXPECT_NEAR(top, bottom, 1e-3 * expected);  // the scene is symmetric about z = 0
}

TEST(TwoSided, ASingleSidedPanelIsLitOnItsFrontOnly) {
  const JobResult result = SolvePanel(/*two_sided=*/false);
  ASSERT_EQ(result.job->scene.faces.size(), 3u);
  const double expected = 0.5 * std::numbers::pi * kParallelSquares;
  EXPECT_NEAR(FaceRadiosity(result, 2), expected, 0.01 * expected);
}

TEST(TwoSided, BothCastersHitTheTwinThatFacesTheRay) {
  absl::StatusOr<Scene> scene = LoadObjText(kPanelObj, kPanelMtl, "panel.obj");
  ASSERT_TRUE(scene.ok());
  ImportOptions import;
  import.two_sided = true;
  ASSERT_TRUE(ApplyImportRules(import, *scene).ok());
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(*scene, MeshOptions{});
  ASSERT_TRUE(mesh.ok());
  absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> embree = EmbreeRayCaster::Create(*mesh);
  ASSERT_TRUE(embree.ok());
  const BruteForceRayCaster brute(*mesh);
  for (const RayCaster* caster : {static_cast<const RayCaster*>(embree->get()),
                                  static_cast<const RayCaster*>(&brute)}) {
    // Downwards from between the top lamp and the panel: the panel's front (patch 2).
    EXPECT_EQ(caster->Intersect({{0.3, 0.6, 0.5}, {0, 0, -1}}).patch, 2u);
    // Upwards from below it: the panel's twin (patch 5), not the panel's back.
    EXPECT_EQ(caster->Intersect({{0.3, 0.6, -0.5}, {0, 0, 1}}).patch, 5u);
    // From a point on the panel, away from it on either side: its twin does not occlude.
    EXPECT_FALSE(caster->Occluded({{0.3, 0.6, 0}, {0, 0, 1}, 1e-6, 0.9}));
    EXPECT_FALSE(caster->Occluded({{0.3, 0.6, 0}, {0, 0, -1}, 1e-6, 0.9}));
    // Through the panel: blocked from both sides.
    EXPECT_TRUE(caster->Occluded({{0.3, 0.6, 0.5}, {0, 0, -1}, 0, 1}));
    EXPECT_TRUE(caster->Occluded({{0.3, 0.6, -0.5}, {0, 0, 1}, 0, 1}));
  }
}

}  // namespace
}  // namespace radflux
