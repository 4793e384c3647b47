// Partial transmission through alpha cut-outs (issue 19): a patch of opacity alpha
// (Material::opacity) lets a ray through with probability 1 - alpha in every ray query, and
// emits and reflects from its opaque part only (power alpha * A * B).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hierarchical_test_scenes.h"
#include "howell_closed_forms.h"
#include "solver/hierarchical/hierarchical.h"
#include "solver/pipeline.h"
#include "solver/raytrace/brute_force_ray_caster.h"
#include "solver/scene/obj_loader.h"

namespace radflux {
namespace {

// A lamp (L_e 1, black) at z = 2 facing down over a grey floor (rho 0.5) at z = 0; a grey
// receiver at z = 3 facing down, above the lamp's back: it sees the floor around the lamp
// and nothing else. A black plate at z = 2.5 facing down lies between the receiver and all of the floor
// (a ray from the receiver to the floor crosses z = 2.5 within [-2/3, 5/3]^2, inside it).
const char* kRoomObj =
    "o lamp\nusemtl lamp\nv 0 0 2\nv 0 1 2\nv 1 1 2\nv 1 0 2\nf 1 2 3 4\n"
    "o floor\nusemtl grey\nv -4 -4 0\nv 5 -4 0\nv 5 5 0\nv -4 5 0\nf 5 6 7 8\n"
    "o receiver\nusemtl grey\nv 0 0 3\nv 0 1 3\nv 1 1 3\nv 1 0 3\nf 9 10 11 12\n";
const char* kPlateObj =
    "o plate\nusemtl plate\nv -1 -1 2.5\nv 2 -1 2.5\nv 2 2 2.5\nv -1 2 2.5\nf 16 15 14 13\n";
const char* kRoomMtl =
    "newmtl lamp\nKd 0 0 0\nKe 1 1 1\nnewmtl grey\nKd 0.5 0.5 0.5\nnewmtl plate\nKd 0 0 0\n";

constexpr uint32_t kLampFace = 0, kReceiverFace = 2;

// The scene with the plate (when `plate_opacity` > 0) and the lamp at `lamp_opacity`.
Scene Room(double plate_opacity, double lamp_opacity = 1) {
  const std::string obj = std::string(kRoomObj) + (plate_opacity > 0 ? kPlateObj : "");
  absl::StatusOr<Scene> scene = LoadObjText(obj, kRoomMtl, "room.obj");
  EXPECT_TRUE(scene.ok()) << scene.status();
  for (Material& m : scene->materials) {
    if (m.name == "plate") m.opacity = plate_opacity;
    if (m.name == "lamp") m.opacity = lamp_opacity;
  }
  return *std::move(scene);
}

JobOptions Options(FormFactorMethod method) {
  JobOptions options;
  options.mesh.max_edge = 0.25;
  options.mesh.group_faces = false;
  options.form_factors.method = method;
  options.form_factors.rays = 1024;
  options.form_factors.samples = 16;
  options.form_factors.hemicube_res = 128;
  options.form_factors.cutoff = 0;
  options.solver.tolerance = 1e-9;
  return options;
}

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

JobResult Solve(Scene scene, FormFactorMethod method) {
  absl::StatusOr<JobResult> result = RunJob(std::move(scene), Options(method));
  EXPECT_TRUE(result.ok()) << result.status();
  return *std::move(result);
}

const FormFactorMethod kMethods[] = {FormFactorMethod::kMonteCarlo, FormFactorMethod::kAnalytic,
                                     FormFactorMethod::kHemicube};

std::string Name(FormFactorMethod method) {
  return method == FormFactorMethod::kMonteCarlo ? "monte_carlo"
         : method == FormFactorMethod::kAnalytic ? "analytic"
                                                 : "hemicube";
}

TEST(PartialTransmission, AHalfOpaquePlateHalvesTheLightThroughIt) {
  // All of the receiver's light comes through the plate once, from the floor (cosine rays,
  // hemicube cells or analytic columns: the receiver sees no emitter's front), so its B is
  // (1 - alpha) times the unblocked B. The floor's B changes too, by the receiver's light
  // on it, (1 - alpha)^2 rho^2 F_fr F_rf < 0.3% of it. The tolerance is ~4 sigma of the
  // pass-through coin flips alone: the receiver's 16 patches cast >= 16 x 1024 rays
  // (monte_carlo; hemicube 16 x 5 x 64^2 cells; analytic 16 x 144 pairs x 16 rays), of
  // which about half reach the floor: sigma <= 0.5 / sqrt(8000) = 0.6% of the ratio.
  for (FormFactorMethod method : kMethods) {
    const double open = FaceRadiosity(Solve(Room(0), method), kReceiverFace);
    const double half = FaceRadiosity(Solve(Room(0.5), method), kReceiverFace);
    const double opaque = FaceRadiosity(Solve(Room(1), method), kReceiverFace);
    ASSERT_GT(open, 1e-3) << Name(method);
    EXPECT_NEAR(half / open, 0.5, 0.025) << Name(method);
    EXPECT_EQ(opaque, 0) << Name(method) << ": an opaque plate blocks everything";
  }
}

TEST(PartialTransmission, AHalfOpaqueLampEmitsHalfItsLight) {
  // The floor's B is rho E F_fl (plus the receiver's little light): halved when the lamp is
  // half there (light sampling and analytic emitter columns weigh by the emitter's opacity).
  for (FormFactorMethod method : kMethods) {
    const double whole = FaceRadiosity(Solve(Room(0, 1), method), 1);
    const double half = FaceRadiosity(Solve(Room(0, 0.5), method), 1);
    EXPECT_NEAR(half / whole, 0.5, 0.01) << Name(method);
  }
}

TEST(PartialTransmission, EnergyBalancesWithAPartlyTransparentReflector) {
  // A grey plate at 30% opacity reflects 0.3 of what meets it and lets 0.7 through; the
  // power emitted equals the power absorbed plus escaped, in every method.
  for (FormFactorMethod method : kMethods) {
    Scene scene = Room(0.3);
    for (Material& m : scene.materials) {
      if (m.name == "plate") m.reflectance = {0.5, 0.5, 0.5};
    }
    const JobOptions options = Options(method);
    const JobResult result = Solve(std::move(scene), method);
    const EnergyBalance balance =
        ComputeEnergyBalance(result.System(), result.solve.radiosity,
                             {SampledRays(options.form_factors),
                              LightSamplesPerRow(options.form_factors)});
    EXPECT_TRUE(balance.Ok()) << Name(method) << ": " << balance.OffMessage();
    EXPECT_LT(balance.RelativeImbalance(), 1e-3) << Name(method);
    // The plate's opaque area is 0.3 of its area, and the lamp's power is A E.
    EXPECT_NEAR(balance.emitted[0], std::numbers::pi, 1e-9);
  }
}

TEST(PartialTransmission, RowsAreBitIdenticalForAnyPartitionOfTheWork) {
  // Pass-through is decided by a hash of ray and patch, not by shared random state: rows
  // built on one thread in blocks of 7 equal those on two threads in blocks of 64.
  for (FormFactorMethod method : kMethods) {
    JobOptions options = Options(method);
    options.form_factors.rays = 64;
    options.form_factors.hemicube_res = 16;
    options.form_factors.samples = 4;
    const auto rows = [&](int threads, int block_size) {
      Scene scene = Room(0.5);
      for (Material& m : scene.materials) {
        if (m.name == "plate") m.reflectance = {0.5, 0.5, 0.5};
      }
      options.form_factors.threads = threads;
      options.form_factors.block_size = block_size;
      absl::StatusOr<JobResult> result = RunJob(std::move(scene), options);
      EXPECT_TRUE(result.ok()) << result.status();
      return result.ok() ? std::move(result->form_factors) : CsrMatrix{};
    };
    const CsrMatrix one = rows(1, 7), two = rows(2, 64);
    ASSERT_GT(one.nnz(), 0u) << Name(method);
    EXPECT_EQ(one.row_begin, two.row_begin) << Name(method);
    EXPECT_EQ(one.col, two.col) << Name(method);
    EXPECT_EQ(one.value, two.value) << Name(method);
  }
}

// The hierarchical solver on HierarchicalClosedForm's pair: a 1 x 1 receiver "a" (rho 0.5)
// under a 1 x 1 lamp "b" 1 above it (the receiver's mean B is rho E F), the lamp at
// `lamp_opacity`, and when `plate_opacity` > 0 a black 3 x 3 plate halfway between them
// (every ray between the two crosses it). Returns the F read back from the receiver's B.
double HierarchicalF(double plate_opacity, double lamp_opacity) {
  int next = 1;
  std::string obj =
      testing::ObjQuad("a", "white", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += testing::ObjQuad("b", "lamp", {{-.5, -.5, 1}, {-.5, .5, 1}, {.5, .5, 1}, {.5, -.5, 1}}, next);
  if (plate_opacity > 0) {
    obj += testing::ObjQuad("plate", "black",
                            {{-1.5, -1.5, .5}, {1.5, -1.5, .5}, {1.5, 1.5, .5}, {-1.5, 1.5, .5}}, next);
  }
  Scene scene =
      testing::SceneFromObj(obj, std::string(testing::kPlateMtl) + "newmtl black\nKd 0 0 0\n");
  for (Material& m : scene.materials) {
    if (m.name == "black") m.opacity = plate_opacity;
    if (m.name == "lamp") m.opacity = lamp_opacity;
  }
  const HierarchicalResult r = testing::SolvedHierarchical(scene, 1e-4, 16);
  return testing::GatheredFormFactor(scene, r);
}

TEST(PartialTransmission, TheHierarchicalSolverLetsTheTransparentShareThrough) {
  // Its links' shadow rays pass the half-opaque plate half the time: the receiver gets half
  // the light. Unblocked, F is the closed form within HierarchicalClosedForm's 0.002. The
  // tolerance on the ratio is 4.5 sigma of its spread over seeds 1-16 (0.0013, mean 0.4999).
  const double exact = testing::ParallelRectangles(1, 1, 1);
  const double open = HierarchicalF(0, 1), half = HierarchicalF(0.5, 1);
  EXPECT_NEAR(open, exact, 0.002);
  EXPECT_NEAR(half / open, 0.5, 0.006);
  EXPECT_EQ(HierarchicalF(1, 1), 0) << "an opaque plate blocks everything";
  // A half-opaque lamp sends from its opaque half only: links to it carry its opacity.
  EXPECT_NEAR(HierarchicalF(0, 0.5) / open, 0.5, 1e-3);
}

TEST(PartialTransmission, TheHierarchicalJobSolvesPartlyTransparentFacesAsTheyAre) {
  // Through RunJob (`--solver hierarchical`): nothing is made opaque or logged, and the
  // receiver of the room scene gets light through the half-opaque plate (about half of the
  // unblocked; the solver's own error on this scene is a few percent either way).
  JobOptions options = Options(FormFactorMethod::kMonteCarlo);
  options.hierarchical.enabled = true;
  absl::StatusOr<JobResult> open = RunJob(Room(0), options);
  absl::StatusOr<JobResult> half = RunJob(Room(0.5), options);
  ASSERT_TRUE(open.ok() && half.ok());
  EXPECT_TRUE(half->job->scene.import_log.Lines().empty());
  EXPECT_NEAR(FaceRadiosity(*half, kReceiverFace) / FaceRadiosity(*open, kReceiverFace), 0.5, 0.1);
}

TEST(PartialTransmission, BothCastersLetTheSameRaysThroughAtTheRate) {
  // 4,096 rays straight up from under the plate, stopping short of the receiver: Embree and the brute-force caster agree on
  // each one, and the fraction that passes is 1 - alpha within 4 sigma.
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(Room(0.3), MeshOptions{});
  ASSERT_TRUE(mesh.ok());
  absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> embree = EmbreeRayCaster::Create(*mesh);
  ASSERT_TRUE(embree.ok());
  const BruteForceRayCaster brute(*mesh);
  int passed = 0;
  constexpr int kSide = 64;
  for (int a = 0; a < kSide; ++a) {
    for (int b = 0; b < kSide; ++b) {
      const Ray ray{{-1 + (a + 0.5) * 3 / kSide, -1 + (b + 0.5) * 3 / kSide, 2.4}, {0, 0, 1}, 0, 0.5};
      const bool occluded = (*embree)->Occluded(ray);
      EXPECT_EQ(occluded, brute.Occluded(ray)) << a << " " << b;
      EXPECT_EQ((*embree)->Intersect(ray).patch == kNoPatch, !occluded) << a << " " << b;
      passed += !occluded;
    }
  }
  const double n = kSide * kSide, sigma = std::sqrt(0.3 * 0.7 / n);
  EXPECT_NEAR(passed / n, 0.7, 4 * sigma);
  // The lamp is opaque: nothing passes it.
  EXPECT_TRUE((*embree)->Occluded({{0.5, 0.5, 1}, {0, 0, 1}, 0, 10}));
}

}  // namespace
}  // namespace radflux
