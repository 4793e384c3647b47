#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>

#include "solver/output/ply_writer.h"
#include "solver/output/vertex_radiosity.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddGridFace;
using output_testing::AddTriangleFace;
using output_testing::ShadeOneMaterial;
using output_testing::TempPath;

// A just-enough reader for the writer's layout: header lines, then the binary body.
struct PlyFile {
  std::vector<std::string> header;
  size_t vertices = 0, faces = 0;
  std::string body;
};

PlyFile ReadPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  PlyFile ply;
  std::string line;
  while (std::getline(in, line) && line != "end_header") {
    ply.header.push_back(line);
    std::istringstream words(line);
    std::string keyword, element;
    size_t count = 0;
    if (words >> keyword >> element >> count && keyword == "element") {
      (element == "vertex" ? ply.vertices : ply.faces) = count;
    }
  }
  std::ostringstream rest;
  rest << in.rdbuf();
  ply.body = rest.str();
  return ply;
}

template <typename T>
T Take(const std::string& body, size_t& offset) {
  T value;
  std::memcpy(&value, body.data() + offset, sizeof(T));
  offset += sizeof(T);
  return value;
}

TEST(OutputPly, WrittenFileParsesBackWithCountsAndValues) {
  PatchMesh mesh;
  AddGridFace(mesh);
  AddTriangleFace(mesh);
  const std::vector<Rgb> b = {{1, 2, 3}, {2, 3, 4}, {3, 4, 5}, {4, 5, 6}, {0.5, 0.25, 8}};
  ToneMapOptions tone;
  tone.scale = 0.5;
  const std::string path = TempPath("mesh.ply");
  ASSERT_TRUE(WritePly(path, mesh, ShadeOneMaterial(mesh), b, tone).ok());

  const PlyFile ply = ReadPly(path);
  ASSERT_GE(ply.header.size(), 2u);
  EXPECT_EQ(ply.header[0], "ply");
  EXPECT_EQ(ply.header[1], "format binary_little_endian 1.0");
  EXPECT_EQ(ply.vertices, 12u);
  EXPECT_EQ(ply.faces, 5u);
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property float radiosity_r"),
            ply.header.end());
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property uchar red"),
            ply.header.end());
  const std::vector<Rgb> expected = *VertexRadiosity(mesh, ShadeOneMaterial(mesh), b);
  size_t offset = 0;
  for (size_t i = 0; i < ply.vertices; ++i) {
    for (int k = 0; k < 3; ++k)
      EXPECT_FLOAT_EQ(Take<float>(ply.body, offset), mesh.positions[i][k]);
    const Vec3 normal = mesh.patches[i < 9 ? 0 : 4].normal;
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(Take<float>(ply.body, offset), normal[k]);
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(Take<float>(ply.body, offset), expected[i][k]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(Take<uint8_t>(ply.body, offset),
                ToneMapByte(expected[i][k] / std::numbers::pi, tone));
    }
  }
  for (size_t f = 0; f < ply.faces; ++f) {
    const Patch& patch = mesh.patches[f];
    ASSERT_EQ(Take<uint8_t>(ply.body, offset), patch.VertexCount());
    for (int k = 0; k < patch.VertexCount(); ++k) {
      EXPECT_EQ(Take<int32_t>(ply.body, offset), static_cast<int32_t>(patch.v[k]));
    }
  }
  EXPECT_EQ(offset, ply.body.size());
  // Spot check a tone-mapped colour: vertex 11 is the triangle's, B_b = 8, scale 0.5.
  EXPECT_EQ(ToneMapByte(8 / std::numbers::pi, tone), 255);
}

TEST(OutputPly, UnwritableDirectoryNamesTheFile) {
  PatchMesh mesh;
  AddGridFace(mesh);
  const std::string path = "/nonexistent_radflux_dir/mesh.ply";
  const absl::Status status =
      WritePly(path, mesh, ShadeOneMaterial(mesh), std::vector<Rgb>(4, Rgb{1, 1, 1}), {});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find(path), std::string::npos) << status;
  EXPECT_NE(status.message().find("PLY"), std::string::npos) << status;
}

}  // namespace
}  // namespace radflux
