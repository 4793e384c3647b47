#include <gtest/gtest.h>

#include <cmath>

#include "solver/output/gouraud_means.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddFace;
using output_testing::AddQuadGridFace;
using output_testing::AddTJunctionWall;
using output_testing::ShadeOneMaterial;

double Linear(const Vec3& p) { return 2 + 0.5 * p.x - 0.25 * p.y; }

// The bilinear interpolant of a linear function is that function on any planar quad, so its
// mean over the quad is the function at the quad's area centroid: a trapezoid's weights are not
// 1/4 (their sum with the corners' values is).
TEST(OutputGouraudMeans, WeightsGiveALinearFieldItsValueAtTheCentroid) {
  PatchMesh mesh;
  AddFace(mesh, {{0, 0, 0}, {4, 0, 0}, {3, 2, 0}, {1, 2, 0}}, {{0, 1, 2, 3}}, {0, 0, 1});
  AddFace(mesh, {{5, 0, 0}, {7, 0, 0}, {8, 1, 0}, {6, 1, 0}}, {{0, 1, 2, 3}}, {0, 0, 1});
  AddFace(mesh, {{0, 5, 0}, {3, 5, 0}, {0, 7, 0}}, {{0, 1, 2, 2}}, {0, 0, 1});
  const ShadingMesh shading = ShadeOneMaterial(mesh);
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const PatchMeanWeights w = GouraudMeanWeights(mesh, shading, p);
    ASSERT_EQ(w.n, mesh.patches[p].VertexCount());
    double sum = 0, mean = 0;
    for (int c = 0; c < w.n; ++c) {
      sum += w.weight[c];
      mean += w.weight[c] * Linear(mesh.Vertex(p, c));
    }
    EXPECT_NEAR(sum, 1, 1e-14) << "patch " << p;
    EXPECT_NEAR(mean, Linear(mesh.patches[p].centroid), 1e-12) << "patch " << p;
  }
  EXPECT_NE(GouraudMeanWeights(mesh, shading, 0).weight[0], 0.25);  // the trapezoid
  for (double w : GouraudMeanWeights(mesh, shading, 1).weight) EXPECT_NEAR(w, 0.25, 1e-15);
}

// ApplyTransposed is Apply's transpose: <T x, y> = <x, T' y> for any x, y.
TEST(OutputGouraudMeans, TJunctionTransposeIsTheAdjoint) {
  PatchMesh wall;
  AddTJunctionWall(wall);
  const ShadingMesh shading = ShadeOneMaterial(wall);
  ASSERT_FALSE(shading.t_junctions.empty());
  const TJunctionMap map(wall, shading);
  std::vector<Rgb> x(shading.size()), y(shading.size());
  for (size_t v = 0; v < x.size(); ++v) {
    x[v] = {std::sin(1.0 + v), std::cos(2.0 * v), 0.1 * v};
    y[v] = {std::cos(3.0 + v), 1.0 / (1 + v), std::sin(0.5 * v)};
  }
  std::vector<Rgb> tx = x, ty = y;
  map.Apply(tx);
  map.ApplyTransposed(ty);
  for (int k = 0; k < kBands; ++k) {
    double left = 0, right = 0;
    for (size_t v = 0; v < x.size(); ++v) left += tx[v][k] * y[v][k], right += x[v][k] * ty[v][k];
    EXPECT_NEAR(left, right, 1e-12) << "band " << k;
  }
}

}  // namespace
}  // namespace radflux
