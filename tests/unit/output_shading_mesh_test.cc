#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "solver/output/export_mesh.h"
#include "solver/output/shading_mesh.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddFace;
using output_testing::AddQuadGridFace;
using output_testing::AddTJunctionWall;
using output_testing::ShadeOneMaterial;

// Welded ids of the positions lying on the line x = 1.
std::set<uint32_t> WeldedOnLineX1(const PatchMesh& mesh, const ShadingMesh& shading,
                                  size_t* positions) {
  std::set<uint32_t> ids;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (mesh.positions[i].x != 1) continue;
    ids.insert(shading.welded[i]);
    ++*positions;
  }
  return ids;
}

TEST(OutputShadingMesh, WeldingKeepsTheVerticesOfASharedEdgeSingle) {
  PatchMesh mesh;  // two coplanar 3x3 faces sharing the edge x = 1
  AddQuadGridFace(mesh, 0, 1, 3, 0, 1, 3);
  AddQuadGridFace(mesh, 1, 2, 3, 0, 1, 3);
  const ShadingMesh shading = ShadeOneMaterial(mesh);
  size_t on_edge = 0;
  EXPECT_EQ(WeldedOnLineX1(mesh, shading, &on_edge).size(), 4u);
  EXPECT_EQ(on_edge, 8u);                  // each face has its own four
  EXPECT_EQ(shading.size(), 2 * 16u - 4);  // ... welded into four
  EXPECT_TRUE(shading.t_junctions.empty());
  for (const Vec3& n : shading.normals) EXPECT_EQ(n, Vec3(0, 0, 1));
  // The second face's vertex (1, 1/3) is 1e-9 off the first's: still one vertex.
  mesh.positions[16 + 4].y += 1e-9;
  on_edge = 0;
  EXPECT_EQ(WeldedOnLineX1(mesh, ShadeOneMaterial(mesh), &on_edge).size(), 4u);
}

TEST(OutputShadingMesh, DifferentMaterialsAndCreasesAreNotWelded) {
  PatchMesh flat;
  AddQuadGridFace(flat, 0, 1, 1, 0, 1, 1);
  AddQuadGridFace(flat, 1, 2, 1, 0, 1, 1);
  auto by_material = BuildShadingMesh(flat, {0, 1});
  ASSERT_TRUE(by_material.ok());
  EXPECT_EQ(by_material->size(), 8u);
  // A second face bent up about x = 1 by 20 degrees (welded) and by 40 degrees (not).
  for (double degrees : {20.0, 40.0}) {
    const double a = degrees * M_PI / 180;
    const Vec3 normal{-std::sin(a), 0, std::cos(a)};
    PatchMesh bent;
    AddQuadGridFace(bent, 0, 1, 1, 0, 1, 1);
    AddFace(bent,
            {{1, 0, 0},
             {1 + std::cos(a), 0, std::sin(a)},
             {1 + std::cos(a), 1, std::sin(a)},
             {1, 1, 0}},
            {{0, 1, 2, 3}}, normal);
    const ShadingMesh shading = ShadeOneMaterial(bent);
    EXPECT_EQ(shading.size(), degrees < 30 ? 6u : 8u) << degrees;
    if (degrees < 30) {  // the shared vertices' normal is the mean of the two faces'
      const Vec3 mean = Normalize(Vec3{0, 0, 1} + normal);
      EXPECT_NEAR(Length(shading.normals[shading.welded[1]] - mean), 0, 1e-12);
    }
  }
}

TEST(OutputShadingMesh, TJunctionsAreFoundAndInsertedIntoTheOutlines) {
  PatchMesh mesh;
  AddTJunctionWall(mesh);
  const ShadingMesh shading = ShadeOneMaterial(mesh);
  // A's three edge patches hold y = 0.25, 0.5, 0.75; B's lower and C's upper patch hold
  // A's y = 1/3 and 2/3. B and C share y = 0.5 and their two vertices there are welded.
  ASSERT_EQ(shading.t_junctions.size(), 5u);
  std::multiset<double> ys;
  for (const TJunction& j : shading.t_junctions) {
    ys.insert(mesh.positions[shading.representative[j.vertex]].y);
    EXPECT_GT(j.t, 0);
    EXPECT_LT(j.t, 1);
  }
  EXPECT_EQ(ys, (std::multiset<double>{0.25, 1 / 3.0, 0.5, 2 / 3.0, 0.75}));
  // A's middle edge patch (x in [1,2], y in [1/3, 2/3]) is a pentagon through (2, 0.5).
  const std::vector<uint32_t> outline = PatchOutline(mesh, shading, 3);
  ASSERT_EQ(outline.size(), 5u);
  EXPECT_EQ(mesh.positions[shading.representative[outline[2]]], Vec3(2, 0.5, 0));
}

TEST(OutputShadingMesh, ExportedTrianglesShareEveryInteriorEdgeSoViewersDoNotCrack) {
  PatchMesh mesh;
  AddTJunctionWall(mesh);
  const ShadingMesh shading = ShadeOneMaterial(mesh);
  auto lit = BuildExportMesh(mesh, shading, std::vector<Rgb>(mesh.size(), Rgb{1, 1, 1}));
  ASSERT_TRUE(lit.ok()) << lit.status();
  const std::vector<uint32_t> triangles = TriangulateExportMesh(*lit);
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  double area = 0;
  for (size_t t = 0; t < triangles.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = triangles[t + k], b = triangles[t + (k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
    const Vec3& p = lit->positions[triangles[t]];
    const double twice =
        Cross(lit->positions[triangles[t + 1]] - p, lit->positions[triangles[t + 2]] - p).z;
    EXPECT_GT(twice, 0) << "triangle " << t / 3 << " is degenerate or flipped";
    area += twice / 2;
  }
  EXPECT_NEAR(area, 3, 1e-12);
  for (const auto& [edge, count] : uses) {
    const Vec3 a = lit->positions[edge.first], b = lit->positions[edge.second];
    const bool outer =
        (a.x == b.x && (a.x == 0 || a.x == 3)) || (a.y == b.y && (a.y == 0 || a.y == 1));
    EXPECT_EQ(count, outer ? 1 : 2) << "edge " << a.x << "," << a.y << " - " << b.x << "," << b.y;
  }
}

TEST(OutputShadingMesh, MismatchedMaterialsAreAnError) {
  PatchMesh mesh;
  AddTJunctionWall(mesh);
  EXPECT_FALSE(BuildShadingMesh(mesh, {0}).ok());
  ShadingOptions options;
  options.weld_tolerance = 0;
  EXPECT_FALSE(BuildShadingMesh(mesh, {0, 0, 0}, options).ok());
}

}  // namespace
}  // namespace radflux
