#include <gtest/gtest.h>

#include <fstream>

#include "solver/output/patch_values_csv.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddGridFace;
using output_testing::AddTriangleFace;
using output_testing::TempPath;

struct Fixture {
  Scene scene;
  PatchMesh mesh;
  std::vector<Rgb> b;
};

Fixture MakeFixture() {
  Fixture f;
  f.scene.objects = {"floor", "odd, \"quoted\" name"};
  f.scene.faces.resize(2);
  f.scene.faces[0].object = 0;
  f.scene.faces[1].object = 1;
  AddGridFace(f.mesh);
  AddTriangleFace(f.mesh);
  f.b = {{1.0 / 3, 2e-300, 0}, {123456789.123, 1, 2}, {0.1, 0.2, 0.3}, {4, 5, 6}, {7, 8, 9e10}};
  return f;
}

TEST(OutputCsv, HeaderIsExactAndRowsRoundTrip) {
  const Fixture f = MakeFixture();
  const std::string path = TempPath("patches.csv");
  ASSERT_TRUE(WritePatchValuesCsv(path, f.scene, f.mesh, f.b).ok());
  std::ifstream in(path);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first, "patch,face,object,area,cx,cy,cz,r,g,b");
  EXPECT_EQ(second, "0,0,floor,2,0.5,1,0,0.333333333,2e-300,0");

  auto rows = ReadPatchValuesCsv(path);
  ASSERT_TRUE(rows.ok()) << rows.status();
  ASSERT_EQ(rows->size(), f.mesh.size());
  for (uint32_t p = 0; p < f.mesh.size(); ++p) {
    const PatchValue& row = (*rows)[p];
    const Patch& patch = f.mesh.patches[p];
    EXPECT_EQ(row.patch, p);
    EXPECT_EQ(row.face, patch.face);
    EXPECT_EQ(row.object, f.scene.objects[patch.face]);
    EXPECT_NEAR(row.area, patch.area, 1e-9 * patch.area);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(row.centroid[k], patch.centroid[k], 1e-8 * (1 + std::abs(patch.centroid[k])));
      EXPECT_NEAR(row.radiosity[k], f.b[p][k], 5e-9 * std::abs(f.b[p][k]));
    }
  }
  EXPECT_EQ((*rows)[4].object, "odd, \"quoted\" name");
}

TEST(OutputCsv, ReaderRejectsBadFilesWithFileAndLine) {
  const std::string path = TempPath("bad.csv");
  std::ofstream(path) << "patch,face,object,area,cx,cy,cz,r,g,b\n0,0,floor,1,2,3\n";
  auto rows = ReadPatchValuesCsv(path);
  ASSERT_FALSE(rows.ok());
  EXPECT_NE(rows.status().message().find(path + ":2:"), std::string::npos) << rows.status();
  std::ofstream(path) << "patch,face\n";
  EXPECT_FALSE(ReadPatchValuesCsv(path).ok());
  EXPECT_FALSE(ReadPatchValuesCsv(TempPath("missing.csv")).ok());
}

TEST(OutputCsv, UnwritableDirectoryAndSizeMismatchAreErrors) {
  const Fixture f = MakeFixture();
  const std::string path = "/nonexistent_radflux_dir/patches.csv";
  const absl::Status s = WritePatchValuesCsv(path, f.scene, f.mesh, f.b);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find(path), std::string::npos) << s;
  EXPECT_FALSE(WritePatchValuesCsv(TempPath("x.csv"), f.scene, f.mesh, {{1, 1, 1}}).ok());
}

}  // namespace
}  // namespace radflux
