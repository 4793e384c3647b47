// Adaptive meshing: on the closed forms it meets the uniform analytic tolerances; the
// furnace stays exact through incremental row updates (threshold 0 splits every patch and
// only new rows and entries pointing at new patches are computed); the lit meshes of both
// adaptive and hierarchical are conforming (no vertex inside another patch's edge).
#include "solver/adaptive/adaptive_refine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "hierarchical_test_scenes.h"
#include "howell_closed_forms.h"
#include "solver/hierarchical/hierarchical.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux {
namespace {

AdaptiveResult Adapted(const Scene& scene, int64_t patches, int passes, double threshold,
                       FormFactorMethod method = FormFactorMethod::kAnalytic) {
  MeshOptions mesh;
  mesh.target_patches = patches;
  FormFactorOptions ff;
  ff.method = method;
  ff.rays = 1024;
  ff.samples = 16;
  ff.cutoff = 0;
  SolverOptions solver;
  solver.tolerance = 1e-9;
  solver.max_iterations = 10000;
  AdaptiveOptions options;
  options.passes = passes;
  options.threshold = threshold;
  absl::StatusOr<AdaptiveResult> r = SolveAdaptive(scene, mesh, ff, solver, options);
  EXPECT_TRUE(r.ok()) << r.status();
  return r.ok() ? *std::move(r) : AdaptiveResult{};
}

double ReceiverFormFactor(const Scene& scene, const AdaptiveResult& r) {
  return testing::ObjectMean(scene, r.leaf_mesh, r.leaf_radiosity, "a") / (0.5 * std::numbers::pi);
}

TEST(AdaptiveRefine, ParallelSquaresWithinAnalyticTolerance) {
  for (double d : {0.5, 1.0, 2.0}) {
    const Scene scene = testing::EmittingParallelSquares(d);
    const AdaptiveResult r = Adapted(scene, 32, 2, 0.05);
    const double exact = testing::ParallelRectangles(1, 1, d);
    std::printf("parallel d=%g exact %.6f adaptive %.6f (%zu patches)\n", d, exact,
                ReceiverFormFactor(scene, r), r.leaves.size());
    EXPECT_NEAR(ReceiverFormFactor(scene, r), exact, 0.002);
    EXPECT_GT(r.leaves.size(), 32u);  // something was split
  }
}

TEST(AdaptiveRefine, PerpendicularPlatesWithinAnalyticTolerance) {
  const Scene scene = testing::EmittingPerpendicularPlates(1, 0.7, 1.3);
  const AdaptiveResult r = Adapted(scene, 64, 2, 0.05);
  const double exact = testing::PerpendicularRectangles(1, 0.7, 1.3);
  std::printf("perpendicular exact %.6f adaptive %.6f (%zu patches)\n", exact,
              ReceiverFormFactor(scene, r), r.leaves.size());
  EXPECT_NEAR(ReceiverFormFactor(scene, r), exact, 0.004);
}

// With a ray-hit method the rows of new patches, and of old patches that point at a split
// one, are rebuilt whole by that method's builder on the new leaves; the emitter is never
// split (its E dominates, and each emitter leaf is a column of every row). Monte Carlo with
// k = 1024 has a standard error of ~0.3% of F here; emitter columns are analytic (s = 16),
// so the closed form holds to the analytic tolerance.
TEST(AdaptiveRefine, MonteCarloRowsRebuiltAndEmitterKept) {
  const Scene scene = testing::EmittingParallelSquares(1.0);
  const AdaptiveResult coarse = Adapted(scene, 32, 0, 0.05, FormFactorMethod::kMonteCarlo);
  const AdaptiveResult r = Adapted(scene, 32, 2, 0.05, FormFactorMethod::kMonteCarlo);
  auto emitter_leaves = [&](const AdaptiveResult& a) {
    size_t count = 0;
    for (uint32_t leaf : a.leaves)
      count += scene.materials[scene.faces[a.tree.nodes[leaf].face].material].IsEmitter();
    return count;
  };
  EXPECT_EQ(emitter_leaves(r), emitter_leaves(coarse));
  EXPECT_GT(r.leaves.size(), coarse.leaves.size());
  ASSERT_EQ(r.passes.size(), 3u);
  EXPECT_GT(r.passes[1].split, 0u);
  // Every receiver row is new or pointed at nothing split (only the emitter is seen): the
  // receiver's rows hold only emitter columns, so just new rows are rebuilt.
  EXPECT_EQ(r.passes[1].rows_recomputed, 4 * r.passes[1].split);
  const double exact = testing::ParallelRectangles(1, 1, 1.0);
  EXPECT_NEAR(ReceiverFormFactor(scene, r), exact, 0.002);
}

// Threshold 0 splits every patch: new rows in full, other rows only where they point at
// split patches. Sample points are fixed per element, so closed-cube rows still sum to 1
// and the furnace holds to the uniform analytic solve's 1e-6.
TEST(AdaptiveRefine, FurnaceExactThroughIncrementalRows) {
  const AdaptiveResult r = Adapted(testing::FurnaceCube(), 24, 1, 0);
  ASSERT_EQ(r.passes.size(), 2u);
  EXPECT_EQ(r.leaves.size(), 96u);
  EXPECT_EQ(r.passes[1].split, 24u);
  const double exact = std::numbers::pi / (1 - 0.5);
  double worst = 0;
  for (const Rgb& b : r.leaf_radiosity) worst = std::max(worst, std::abs(b[0] / exact - 1));
  EXPECT_LT(worst, 1e-6);
}

// A box standing on a floor: a floor element that crosses the box's footprint straddles a
// contact line (some probe rays start under the box and hit its inside first); elements
// fully outside or fully under it do not.
TEST(AdaptiveRefine, ContactLinesAreFound) {
  int next = 1;
  std::string obj =
      testing::ObjQuad("floor", "white", {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, next);
  const double h = 0.25;
  obj += testing::ObjQuad("box", "white", {{h, -h, 0}, {h, h, 0}, {h, h, 0.5}, {h, -h, 0.5}}, next);
  obj += testing::ObjQuad("box", "white", {{-h, -h, 0}, {-h, -h, 0.5}, {-h, h, 0.5}, {-h, h, 0}},
                          next);
  obj += testing::ObjQuad("box", "white", {{h, h, 0}, {-h, h, 0}, {-h, h, 0.5}, {h, h, 0.5}}, next);
  obj += testing::ObjQuad("box", "white", {{-h, -h, 0}, {h, -h, 0}, {h, -h, 0.5}, {-h, -h, 0.5}},
                          next);
  obj += testing::ObjQuad("box", "white", {{-h, -h, 0.5}, {h, -h, 0.5}, {h, h, 0.5}, {-h, h, 0.5}},
                          next);
  obj += testing::ObjQuad("lamp", "lamp", {{-.5, -.5, 3}, {-.5, .5, 3}, {.5, .5, 3}, {.5, -.5, 3}},
                          next);
  const Scene scene = testing::SceneFromObj(obj, testing::kPlateMtl);
  MeshOptions options;
  options.target_patches = 50;
  const PatchMesh mesh = *SubdivideScene(scene, options);
  const auto caster = *EmbreeRayCaster::Create(mesh);
  auto floor_element = [](double x0, double x1, double y0, double y1) {
    Element e;
    e.corners = {Vec3{x0, y0, 0}, Vec3{x1, y0, 0}, Vec3{x1, y1, 0}, Vec3{x0, y1, 0}};
    e.normal = {0, 0, 1};
    e.area = (x1 - x0) * (y1 - y0);
    return e;
  };
  uint64_t rays = 0;
  const double eps = 1e-6;
  EXPECT_TRUE(StraddlesContact(floor_element(-0.5, 0, -0.1, 0.1), *caster, 16, 7, eps, rays));
  EXPECT_TRUE(StraddlesContact(floor_element(0.1, 0.4, 0.1, 0.4), *caster, 16, 7, eps, rays));
  EXPECT_FALSE(StraddlesContact(floor_element(-0.9, -0.6, -0.1, 0.1), *caster, 16, 7, eps, rays));
  EXPECT_FALSE(StraddlesContact(floor_element(-0.2, 0.2, -0.2, 0.2), *caster, 16, 7, eps, rays));
  EXPECT_EQ(rays, 64u);
}

// No vertex of the mesh lies strictly inside an edge of a patch of the same face.
void ExpectConforming(const PatchMesh& mesh) {
  size_t bad = 0;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    const uint32_t f = patch.face;
    for (int k = 0; k < patch.VertexCount(); ++k) {
      const Vec3 a = mesh.Vertex(p, k), b = mesh.Vertex(p, (k + 1) % patch.VertexCount());
      const double len2 = Dot(b - a, b - a);
      for (uint32_t v = mesh.face_first_vertex[f]; v < mesh.face_first_vertex[f + 1]; ++v) {
        const Vec3 x = mesh.positions[v];
        const double t = Dot(x - a, b - a) / len2;
        if (t <= 1e-9 || t >= 1 - 1e-9) continue;
        const Vec3 off = x - (a + (b - a) * t);
        if (Dot(off, off) < 1e-18 * len2) ++bad;
      }
    }
  }
  EXPECT_EQ(bad, 0u) << "T-junctions in the lit mesh";
}

TEST(AdaptiveRefine, LitMeshesAreConforming) {
  const Scene scene = testing::EmittingPerpendicularPlates(1, 0.7, 1.3);
  const AdaptiveResult a = Adapted(scene, 16, 3, 0.05);
  ExpectConforming(a.mesh);
  HierarchicalOptions h;
  h.link_epsilon = 1e-4;
  absl::StatusOr<HierarchicalResult> hr = SolveHierarchical(scene, h, SolverOptions{});
  ASSERT_TRUE(hr.ok()) << hr.status();
  EXPECT_GT(hr->mesh.size(), hr->leaves.size());  // T-junctions were there and got fans
  ExpectConforming(hr->mesh);
}

}  // namespace
}  // namespace radflux
