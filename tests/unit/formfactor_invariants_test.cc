// Invariants of the form-factor rows: closed enclosures sum to 1, reciprocity,
// occlusion, determinism across thread counts, culling and the cut-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "hard_cases.h"
#include "howell_closed_forms.h"
#include "solver/formfactor/analytic_pair.h"
#include "solver/formfactor/contour_cache.h"
#include "solver/formfactor/polygon_form_factor.h"
#include "solver/formfactor/row_rays.h"
#include "solver/raytrace/brute_force_ray_caster.h"
#include "test_scenes.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::RowFixture;
using testing::SceneFromObj;

// A unit cube with every face looking inwards; face "top" is the lamp.
Scene ClosedCube() {
  int next = 1;
  std::string obj;
  obj += ObjQuad("bottom", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, next);
  obj += ObjQuad("top", "lamp", {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, next);
  obj += ObjQuad("x0", "white", {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, next);
  obj += ObjQuad("x1", "white", {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}, next);
  obj += ObjQuad("y0", "white", {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, next);
  obj += ObjQuad("y1", "white", {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}, next);
  return SceneFromObj(obj);
}

// k = 1024 rays, r = 64, s = 16, no cut-off: the knobs the hard cases use too.
FormFactorOptions Options(FormFactorMethod m) { return testing::HardOptions(m); }

TEST(FormFactorInvariants, ClosedCubeRowsSumToOne) {
  RowFixture fixture(ClosedCube(), MeshOptions{6 * 16, 0});
  for (auto m :
       {FormFactorMethod::kMonteCarlo, FormFactorMethod::kHemicube, FormFactorMethod::kAnalytic}) {
    const CsrMatrix f = fixture.Rows(Options(m));
    double worst = 0;
    for (uint32_t i = 0; i < f.rows; ++i) worst = std::max(worst, std::abs(f.RowSum(i) - 1));
    std::printf("  %-12s max |row sum - 1| = %.2e\n", std::string(MethodName(m)).c_str(), worst);
    // monte_carlo: statistical (k = 1024 rays, and 16 s = 256 light samples for the lamp's
    // columns, which add their own noise). hemicube: its cells
    // partition the hemisphere, but the lamp's column is the exact point form factor, so a row
    // misses 1 by the cells' aliasing of the lamp's outline (a few cells of 1/r^2 each, r = 64).
    // analytic: exact per-point factors, no occluders here.
    const double tolerance = m == FormFactorMethod::kMonteCarlo ? 0.03
                             : m == FormFactorMethod::kHemicube ? 5e-3
                                                                : 2e-3;
    EXPECT_LT(worst, tolerance) << MethodName(m);
  }
}

TEST(FormFactorInvariants, ReciprocityBetweenFacesOfTheCube) {
  RowFixture fixture(ClosedCube(), MeshOptions{6 * 16, 0});
  const double adjacent = testing::PerpendicularRectangles(1, 1, 1);
  const double opposite = testing::ParallelRectangles(1, 1, 1);
  for (auto m :
       {FormFactorMethod::kMonteCarlo, FormFactorMethod::kHemicube, FormFactorMethod::kAnalytic}) {
    const CsrMatrix f = fixture.Rows(Options(m));
    // Equal areas: A_i F_ij = A_j F_ji reduces to F_ij = F_ji for whole faces.
    const double bx = fixture.SurfaceFormFactor(f, "bottom", "x0");
    const double xb = fixture.SurfaceFormFactor(f, "x0", "bottom");
    const double by = fixture.SurfaceFormFactor(f, "bottom", "y1");
    const double yb = fixture.SurfaceFormFactor(f, "y1", "bottom");
    const double x01 = fixture.SurfaceFormFactor(f, "x0", "x1");
    const double x10 = fixture.SurfaceFormFactor(f, "x1", "x0");
    EXPECT_NEAR(bx, xb, 0.01) << MethodName(m);
    EXPECT_NEAR(by, yb, 0.01) << MethodName(m);
    EXPECT_NEAR(x01, x10, 0.01) << MethodName(m);
    EXPECT_NEAR(bx, adjacent, 0.01) << MethodName(m);
    EXPECT_NEAR(x01, opposite, 0.01) << MethodName(m);
  }
}

// Two parallel unit squares one apart and, half-way, a plate covering x > 0. By the
// symmetry (p, q) -> (-p, -q) of the line from p to q, exactly half of the exchange is blocked.
TEST(FormFactorInvariants, HalfPlaneOccluderHalvesTheFormFactor) {
  int next = 1;
  std::string obj;
  obj += ObjQuad("a", "white", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += ObjQuad("b", "white", {{-.5, -.5, 1}, {-.5, .5, 1}, {.5, .5, 1}, {.5, -.5, 1}}, next);
  obj += ObjQuad("wall", "white", {{0, -1, .5}, {1, -1, .5}, {1, 1, .5}, {0, 1, .5}}, next);
  RowFixture fixture(SceneFromObj(obj), MeshOptions{0, 0.125});
  const double open = testing::ParallelRectangles(1, 1, 1);
  for (auto m :
       {FormFactorMethod::kMonteCarlo, FormFactorMethod::kHemicube, FormFactorMethod::kAnalytic}) {
    const CsrMatrix f = fixture.Rows(Options(m));
    EXPECT_NEAR(fixture.SurfaceFormFactor(f, "a", "b"), open / 2, 0.006) << MethodName(m);
  }
}

TEST(FormFactorInvariants, RowsAreBitIdenticalOnOneAndTwoThreads) {
  auto scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok());
  RowFixture fixture(*scene, MeshOptions{600, 0});
  for (auto m :
       {FormFactorMethod::kMonteCarlo, FormFactorMethod::kHemicube, FormFactorMethod::kAnalytic}) {
    FormFactorOptions o = Options(m);
    o.rays = 64;
    o.hemicube_res = 8;
    o.samples = 2;
    o.block_size = 7;
    o.threads = 1;
    const CsrMatrix one = fixture.Rows(o);
    o.threads = 2;
    const CsrMatrix two = fixture.Rows(o);
    EXPECT_EQ(one.row_begin, two.row_begin) << MethodName(m);
    EXPECT_EQ(one.col, two.col) << MethodName(m);
    EXPECT_EQ(one.value, two.value) << MethodName(m);
  }
}

TEST(FormFactorInvariants, CornellBoxRowSumsAndSparsity) {
  auto scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok());
  RowFixture fixture(*scene, MeshOptions{2000, 0});
  FormFactorOptions o = Options(FormFactorMethod::kMonteCarlo);
  o.rays = 256;
  o.cutoff = 1e-6;
  absl::StatusOr<FormFactorResult> result = BuildFormFactors(fixture.context, o);
  ASSERT_TRUE(result.ok());
  const CsrMatrix& f = result->matrix;
  const double mean_area = MeanRowArea(fixture.attributes.area, fixture.context.needs_row);
  double min_sum = 2, max_sum = 0, mean = 0, worst_excess = 0;
  uint32_t fewest = o.rays;
  for (uint32_t i = 0; i < f.rows; ++i) {
    min_sum = std::min(min_sum, f.RowSum(i));
    max_sum = std::max(max_sum, f.RowSum(i));
    mean += f.RowSum(i) / f.rows;
    // A row can exceed one only by noise (its k_i cosine rays plus the emitter columns' light
    // samples): at most 0.01 for k_i = 256, the excess scaling as the noise, 1 / sqrt(k_i).
    const uint32_t k = RowRayCount(o.rays, fixture.attributes.area[i], mean_area,
                                   MaxComponent(fixture.attributes.emission[i]) > 0);
    fewest = std::min(fewest, k);
    worst_excess = std::max(worst_excess, (f.RowSum(i) - 1) * std::sqrt(k / 256.0));
  }
  std::printf(
      "cornell box: %u patches, nnz %zu (%.1f per row), %zu bytes, row sums [%.4f, %.4f] "
      "mean %.4f, dropped %.2e, fewest rays %u, worst excess at 256 rays %.4f\n",
      f.rows, f.nnz(), double(f.nnz()) / f.rows, f.Bytes(), min_sum, max_sum, mean,
      result->stats.dropped_sum, fewest, worst_excess);
  // The box is open at the front: rows sum to less than one, but for noise.
  EXPECT_LE(worst_excess, 0.01);
  EXPECT_LE(max_sum, 1.0 + 0.01 * std::sqrt(256.0 / fewest));
  EXPECT_GT(mean, 0.5);
  EXPECT_LT(mean, 1.0);
  EXPECT_LT(f.nnz(), size_t{f.rows} * f.rows / 4);  // sparse: rays, not all pairs
}

TEST(FormFactorInvariants, PatchesWithoutReflectanceGetNoRow) {
  int next = 1;
  std::string obj;
  obj += ObjQuad("a", "black", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += ObjQuad("b", "white", {{-.5, -.5, 1}, {-.5, .5, 1}, {.5, .5, 1}, {.5, -.5, 1}}, next);
  RowFixture fixture(SceneFromObj(obj), MeshOptions{8, 0});
  const CsrMatrix f = fixture.Rows(Options(FormFactorMethod::kMonteCarlo));
  for (uint32_t i = 0; i < f.rows; ++i) {
    if (fixture.ObjectOf(i) == "a") {
      EXPECT_EQ(f.RowCols(i).size(), 0u);
    } else {
      EXPECT_GT(f.RowCols(i).size(), 0u);
    }
  }
}

TEST(FormFactorInvariants, CutoffDropsSmallEntriesAndReportsTheirSum) {
  RowFixture fixture(ClosedCube(), MeshOptions{6 * 64, 0});
  FormFactorOptions o = Options(FormFactorMethod::kAnalytic);
  o.samples = 4;
  absl::StatusOr<FormFactorResult> all = BuildFormFactors(fixture.context, o);
  o.cutoff = 1e-3;
  absl::StatusOr<FormFactorResult> cut = BuildFormFactors(fixture.context, o);
  ASSERT_TRUE(all.ok() && cut.ok());
  EXPECT_LT(cut->matrix.nnz(), all->matrix.nnz());
  double lost = 0;
  for (uint32_t i = 0; i < all->matrix.rows; ++i)
    lost += all->matrix.RowSum(i) - cut->matrix.RowSum(i);
  EXPECT_NEAR(lost, cut->stats.dropped_sum, 1e-4);
  EXPECT_GT(cut->stats.dropped_sum, 0);
  // Below the cut-off only in emitter columns, which are never cut (issue 20).
  int kept_small = 0;
  for (size_t e = 0; e < cut->matrix.value.size(); ++e) {
    if (cut->matrix.value[e] >= 1e-3f) continue;
    EXPECT_TRUE(fixture.context.emitter[cut->matrix.col[e]]) << "entry " << e;
    ++kept_small;
  }
  std::printf("cut-off 1e-3: %d entries below it kept in emitter columns\n", kept_small);
}

// The shared edge terms give every contour sum bit for bit: adjacent patches' opposite
// terms are exact negations. Rows from three points on each of a few patches, against every
// patch of the cube (clipped or not: the two compute the same unclipped sum).
TEST(FormFactorInvariants, ContourCacheGivesTheDirectContourSumBitForBit) {
  RowFixture fixture(ClosedCube(), MeshOptions{6 * 16, 0});
  const PatchMesh& mesh = fixture.mesh;
  const PatchEdges edges(mesh);
  const PairPatches patches(mesh);
  EXPECT_LT(edges.size(), 4 * mesh.size());  // shared edges are counted once
  ContourCache cache;
  for (uint32_t i = 0; i < mesh.size(); i += 7) {
    const std::vector<Vec3> points = PatchSamplePoints(mesh, i, 3, 5);
    cache.Begin(patches, edges, points, mesh.patches[i].normal);
    for (uint32_t j = 0; j < mesh.size(); ++j) {
      std::vector<Vec3> polygon;
      for (int k = 0; k < mesh.patches[j].VertexCount(); ++k) polygon.push_back(mesh.Vertex(j, k));
      for (size_t m = 0; m < points.size(); ++m) {
        ASSERT_EQ(cache.FormFactor(j, m),
                  UnclippedPointToPolygonFormFactor(points[m], mesh.patches[i].normal, polygon))
            << i << " " << j << " " << m;
      }
    }
  }
}

TEST(EmbreeRayCaster, AgreesWithBruteForce) {
  auto scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok());
  RowFixture fixture(*scene, MeshOptions{300, 0});
  BruteForceRayCaster brute(fixture.mesh);
  int agree = 0, total = 0;
  for (uint32_t i = 0; i < 400; ++i) {
    const Point2 u = MultiJitteredSample(i, 400, 7), w = MultiJitteredSample(i, 400, 9);
    const Ray ray{{278 + 200 * (u.x - .5), 273 + 200 * (u.y - .5), 280},
                  {std::cos(6.283 * w.x), w.y - .5, std::sin(6.283 * w.x)}};
    const Hit a = fixture.caster->Intersect(ray), b = brute.Intersect(ray);
    ++total;
    if (a.patch == b.patch) {
      ++agree;
      EXPECT_NEAR(a.t, b.t, 1e-3 * b.t);
    }
    EXPECT_EQ(fixture.caster->Occluded(ray), brute.Occluded(ray));
  }
  EXPECT_GE(agree, total - 2);  // rays grazing a shared patch edge may pick either neighbour
}

}  // namespace
}  // namespace radflux
