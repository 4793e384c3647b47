#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/output/vertex_radiosity.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddFace;
using output_testing::AddGridFace;
using output_testing::AddQuadGridFace;
using output_testing::AddTJunctionWall;
using output_testing::ShadeOneMaterial;

// A linear field per band; a patch's mean of it is its value at the patch's centroid.
Rgb Linear(const Vec3& p) { return {2 + 0.5 * p.x - 0.25 * p.y, 1 + 0.1 * p.y, 3 - 0.3 * p.x}; }

std::vector<Rgb> LinearPerPatch(const PatchMesh& mesh) {
  std::vector<Rgb> b;
  for (const Patch& patch : mesh.patches) b.push_back(Linear(patch.centroid));
  return b;
}

void ExpectLinearAtEveryVertex(const PatchMesh& mesh) {
  auto v = VertexRadiosity(mesh, ShadeOneMaterial(mesh), LinearPerPatch(mesh));
  ASSERT_TRUE(v.ok()) << v.status();
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Rgb expected = Linear(mesh.positions[i]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR((*v)[i][k], expected[k], 1e-12)
          << "vertex " << mesh.positions[i].x << "," << mesh.positions[i].y << " band " << k;
    }
  }
}

TEST(OutputVertexRadiosity, ExtrapolationReproducesALinearFieldExactlyAtTheBoundary) {
  PatchMesh uneven;  // 2x2 quads of unequal size: every vertex but one is on the boundary
  AddGridFace(uneven);
  ExpectLinearAtEveryVertex(uneven);
  PatchMesh grid;
  AddQuadGridFace(grid, -1, 3, 4, 0, 1.5, 3);
  ExpectLinearAtEveryVertex(grid);
  PatchMesh triangles;  // a quad as four triangles around its centre
  AddFace(triangles, {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {1, 0.5, 0}},
          {{0, 1, 4, 4}, {1, 2, 4, 4}, {2, 3, 4, 4}, {3, 0, 4, 4}}, {0, 0, 1});
  ExpectLinearAtEveryVertex(triangles);
}

TEST(OutputVertexRadiosity, LinearFieldAcrossFacesWithTJunctionsIsExact) {
  PatchMesh wall;
  AddTJunctionWall(wall);
  ExpectLinearAtEveryVertex(wall);
}

// The exact mean over [a, b] of sin(pi t).
double MeanOfSine(double a, double b) {
  return (std::cos(std::numbers::pi * a) - std::cos(std::numbers::pi * b)) /
         (std::numbers::pi * (b - a));
}

TEST(OutputVertexRadiosity, GouraudShadingKeepsTheMeanOfAPeakedField) {
  // B = 0.2 + sin(pi x) sin(pi y) on the unit square in 8 x 8 patches, each given its exact mean:
  // a lit wall's bump, curved everywhere. Gouraud means (a square's corner mean) must carry the
  // patches' power: the fit alone lost 5.6% of the total and up to 6.2% of an inner patch's
  // value; its one deficit step left 0.12% of the total and 8% at the boundary's extrapolated
  // patches; matched (gouraud_means.h), the total is within 0.011% and every patch within 1.84%.
  const int n = 8;
  PatchMesh grid;
  AddQuadGridFace(grid, 0, 1, n, 0, 1, n);
  std::vector<Rgb> b;
  for (const Patch& patch : grid.patches) {
    const double h = 1.0 / n, x = patch.centroid.x - h / 2, y = patch.centroid.y - h / 2;
    const double mean = 0.2 + MeanOfSine(x, x + h) * MeanOfSine(y, y + h);
    b.push_back({mean, mean, mean});
  }
  auto v = VertexRadiosity(grid, ShadeOneMaterial(grid), b);
  ASSERT_TRUE(v.ok()) << v.status();
  double patches = 0, gouraud = 0;
  for (size_t p = 0; p < grid.size(); ++p) {
    double corners = 0;
    for (int c = 0; c < 4; ++c) corners += (*v)[grid.patches[p].v[c]][0] / 4;
    patches += b[p][0], gouraud += corners;
    EXPECT_NEAR(corners / b[p][0], 1, 0.02) << "patch " << p;
  }
  EXPECT_NEAR(gouraud / patches, 1, 2e-4);
}

TEST(OutputVertexRadiosity, ARowOfPatchesGetsNoSlopeAcrossIt) {
  PatchMesh row;  // 3x1: centroids on a line, so only the slope along x is known
  AddQuadGridFace(row, 0, 3, 3, 0, 1, 1);
  auto v = VertexRadiosity(row, ShadeOneMaterial(row), {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}});
  ASSERT_TRUE(v.ok());
  for (size_t i = 0; i < row.positions.size(); ++i) {
    EXPECT_NEAR((*v)[i][0], 0.5 + row.positions[i].x, 1e-12) << i;  // B = x + 0.5, any y
  }
}

TEST(OutputVertexRadiosity, ExtrapolationIsClampedAtZero) {
  PatchMesh row;
  AddQuadGridFace(row, 0, 3, 3, 0, 1, 1);
  auto v = VertexRadiosity(row, ShadeOneMaterial(row), {{0.1, 1, 1}, {2, 2, 2}, {3, 3, 3}});
  ASSERT_TRUE(v.ok());
  EXPECT_EQ((*v)[0][0], 0);  // the fitted line is negative at x = 0
  EXPECT_GT((*v)[0][1], 0);
}

// A lone triangle (a chamfer on a rail's corner in the conference room, 3 m from the origin,
// facing (-1, -1, -1)): its vertices' fit has one patch, whose centroid offsets from its mean
// are rounding noise (1e-14); the pseudo-inverse took that noise as a spread and its slopes
// gave weights of 1e15, and the conference room's PLY had vertices of B = 9e29 (a clamped 0
// or a huge value here). Every vertex of a lone patch shows the patch's value.
TEST(OutputVertexRadiosity, LonePatchesFarFromTheOriginKeepTheirValues) {
  PatchMesh mesh;
  std::vector<Rgb> b;
  for (int k = 0; k < 64; ++k) {  // 64 such triangles, apart, of slightly different sizes
    const Vec3 v0 = Vec3{-200.466, 176.9, 589.753} + Vec3{37.1, 11.3, -23.7} * k;
    const double s = 1.4648 + 0.0137 * k;
    AddFace(mesh, {v0, v0 + Vec3{0, -s, s}, v0 + Vec3{-s, 0, s}}, {{0, 1, 2, 2}},
            Normalize(Vec3{-1, -1, -1}));
    b.push_back({0.3 + 0.01 * k, 0.2, 0.1});
  }
  auto v = VertexRadiosity(mesh, ShadeOneMaterial(mesh), b);
  ASSERT_TRUE(v.ok()) << v.status();
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Rgb& expected = b[i / 3];
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR((*v)[i][k], expected[k], 1e-9 * expected[k]) << i << " band " << k;
    }
  }
}

TEST(OutputVertexRadiosity, CreasesBetweenFacesStaySharp) {
  // Floor (y = 0, facing +y) and wall (z = 0, facing +z) share the geometric edge
  // from (0,0,0) to (1,0,0); 90 degrees is past the crease angle.
  PatchMesh mesh;
  AddFace(mesh, {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, {{0, 1, 2, 3}}, {0, 1, 0});
  AddFace(mesh, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2, 3}}, {0, 0, 1});
  const ShadingMesh shading = ShadeOneMaterial(mesh);
  auto v = VertexRadiosity(mesh, shading, {{1, 1, 1}, {5, 5, 5}});
  ASSERT_TRUE(v.ok()) << v.status();
  for (uint32_t i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ((*v)[i][0], 1) << "floor vertex " << i;
  for (uint32_t i = 4; i < 8; ++i) EXPECT_DOUBLE_EQ((*v)[i][0], 5) << "wall vertex " << i;
  EXPECT_EQ(mesh.positions[0], mesh.positions[4]);  // same point, different values
  EXPECT_EQ(shading.normals[shading.welded[0]], Vec3(0, 1, 0));
  EXPECT_EQ(shading.normals[shading.welded[4]], Vec3(0, 0, 1));
}

TEST(OutputVertexRadiosity, WrongNumberOfValuesIsAnError) {
  PatchMesh mesh;
  AddGridFace(mesh);
  auto v = VertexRadiosity(mesh, ShadeOneMaterial(mesh), {{1, 1, 1}});
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(v.status().message().find("1 values for 4 patches"), std::string::npos);
}

}  // namespace
}  // namespace radflux
