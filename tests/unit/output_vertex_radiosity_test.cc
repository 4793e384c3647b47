#include <gtest/gtest.h>

#include "solver/output/vertex_radiosity.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddFace;
using output_testing::AddGridFace;

TEST(OutputVertexRadiosity, AreaWeightedMeanOfThePatchesAroundEachVertex) {
  PatchMesh mesh;
  AddGridFace(mesh);  // patch areas 2, 4, 1, 2
  ASSERT_DOUBLE_EQ(mesh.patches[1].area, 4);
  const std::vector<Rgb> b = {{1, 10, 0}, {2, 20, 0}, {3, 30, 0}, {4, 40, 0}};
  auto v = VertexRadiosity(mesh, b);
  ASSERT_TRUE(v.ok()) << v.status();
  ASSERT_EQ(v->size(), 9u);
  // Corners take their one patch.
  EXPECT_DOUBLE_EQ((*v)[0][0], 1);
  EXPECT_DOUBLE_EQ((*v)[2][0], 2);
  EXPECT_DOUBLE_EQ((*v)[6][0], 3);
  EXPECT_DOUBLE_EQ((*v)[8][0], 4);
  // Edge midpoints: two patches.
  EXPECT_DOUBLE_EQ((*v)[1][0], (2 * 1 + 4 * 2) / 6.0);  // bottom edge: patches 0, 1
  EXPECT_DOUBLE_EQ((*v)[3][0], (2 * 1 + 1 * 3) / 3.0);  // left edge: patches 0, 2
  EXPECT_DOUBLE_EQ((*v)[5][0], (4 * 2 + 2 * 4) / 6.0);  // right edge: patches 1, 3
  EXPECT_DOUBLE_EQ((*v)[7][0], (1 * 3 + 2 * 4) / 3.0);  // top edge: patches 2, 3
  // Centre: all four.
  EXPECT_DOUBLE_EQ((*v)[4][0], (2 * 1 + 4 * 2 + 1 * 3 + 2 * 4) / 9.0);
  EXPECT_DOUBLE_EQ((*v)[4][1], (2 * 10 + 4 * 20 + 1 * 30 + 2 * 40) / 9.0);
  EXPECT_DOUBLE_EQ((*v)[4][2], 0);
}

TEST(OutputVertexRadiosity, CreasesBetweenFacesStaySharp) {
  // Floor (y = 0, facing +y) and wall (z = 0, facing +z) share the geometric edge
  // from (0,0,0) to (1,0,0), each with its own vertices as PatchMesh guarantees.
  PatchMesh mesh;
  AddFace(mesh, {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, {{0, 1, 2, 3}}, {0, 1, 0});
  AddFace(mesh, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2, 3}}, {0, 0, 1});
  auto v = VertexRadiosity(mesh, {{1, 1, 1}, {5, 5, 5}});
  ASSERT_TRUE(v.ok()) << v.status();
  for (uint32_t i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ((*v)[i][0], 1) << "floor vertex " << i;
  for (uint32_t i = 4; i < 8; ++i) EXPECT_DOUBLE_EQ((*v)[i][0], 5) << "wall vertex " << i;
  EXPECT_EQ(mesh.positions[0], mesh.positions[4]);  // same point, different values
  const std::vector<Vec3> normals = VertexNormals(mesh);
  EXPECT_EQ(normals[0], Vec3(0, 1, 0));
  EXPECT_EQ(normals[4], Vec3(0, 0, 1));
}

TEST(OutputVertexRadiosity, WrongNumberOfValuesIsAnError) {
  PatchMesh mesh;
  AddGridFace(mesh);
  auto v = VertexRadiosity(mesh, {{1, 1, 1}});
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(v.status().message().find("1 values for 4 patches"), std::string::npos);
}

}  // namespace
}  // namespace radflux
