#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <numbers>

#include "solver/output/gltf_writer.h"
#include "solver/output/vertex_radiosity.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddGridFace;
using output_testing::AddTriangleFace;
using output_testing::ShadeOneMaterial;
using output_testing::TempPath;

// The accessor's elements as floats (or raw uint32 bits for indices).
template <typename T>
std::vector<T> AccessorData(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors.at(static_cast<size_t>(index));
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<size_t>(accessor.bufferView));
  const auto& data = model.buffers.at(static_cast<size_t>(view.buffer)).data;
  const size_t components = accessor.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  std::vector<T> values(accessor.count * components);
  std::memcpy(values.data(), data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(T));
  return values;
}

TEST(OutputGlb, TinyGltfLoadsItBackWithColoursAndUnlitMaterial) {
  PatchMesh mesh;
  AddGridFace(mesh);
  AddTriangleFace(mesh);
  const std::vector<Rgb> b = {{1, 2, 3}, {2, 3, 4}, {3, 4, 5}, {4, 5, 6}, {0.5, 0.25, 80}};
  GltfOptions options;
  options.metres_per_unit = 0.001;
  options.tone.scale = 0.5;
  const std::string path = TempPath("mesh.glb");
  ASSERT_TRUE(WriteGlb(path, mesh, ShadeOneMaterial(mesh), b, options).ok());

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path)) << error;
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
  ASSERT_TRUE(primitive.attributes.count("POSITION"));
  ASSERT_TRUE(primitive.attributes.count("NORMAL"));
  ASSERT_TRUE(primitive.attributes.count("COLOR_0"));
  ASSERT_TRUE(primitive.attributes.count("_RADIOSITY"));

  const auto positions = AccessorData<float>(model, primitive.attributes.at("POSITION"));
  const auto colours = AccessorData<float>(model, primitive.attributes.at("COLOR_0"));
  const auto raw = AccessorData<float>(model, primitive.attributes.at("_RADIOSITY"));
  const auto indices = AccessorData<uint32_t>(model, primitive.indices);
  ASSERT_EQ(positions.size(), 3 * mesh.positions.size());
  EXPECT_EQ(model.accessors[static_cast<size_t>(primitive.indices)].componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  ASSERT_EQ(indices.size(), 4u * 6 + 3);  // four quads as two triangles, one triangle
  const std::vector<Rgb> expected = *VertexRadiosity(mesh, ShadeOneMaterial(mesh), b);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_FLOAT_EQ(positions[3 * i + k], mesh.positions[i][k] * 0.001);
      EXPECT_FLOAT_EQ(raw[3 * i + k], expected[i][k]);
      EXPECT_FLOAT_EQ(colours[3 * i + k], std::min(1.0, expected[i][k] / std::numbers::pi * 0.5));
    }
  }
  EXPECT_FLOAT_EQ(colours[3 * 11 + 2], 1.0f);  // B = 80 saturates
  // Quad 0 is split along v1-v3 as Embree splits it.
  const Patch& quad = mesh.patches[0];
  EXPECT_EQ(
      std::vector<uint32_t>(indices.begin(), indices.begin() + 6),
      (std::vector<uint32_t>{quad.v[0], quad.v[1], quad.v[3], quad.v[2], quad.v[3], quad.v[1]}));

  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_TRUE(model.materials[0].extensions.count("KHR_materials_unlit"));
  EXPECT_NE(
      std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_materials_unlit"),
      model.extensionsUsed.end());
  EXPECT_EQ(model.asset.version, "2.0");
}

TEST(OutputGlb, UnwritableDirectoryAndEmptyMeshAreErrors) {
  PatchMesh mesh;
  AddGridFace(mesh);
  const std::string path = "/nonexistent_radflux_dir/mesh.glb";
  const absl::Status status =
      WriteGlb(path, mesh, ShadeOneMaterial(mesh), std::vector<Rgb>(4, Rgb{1, 1, 1}), {});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find(path), std::string::npos) << status;
  EXPECT_FALSE(WriteGlb(TempPath("empty.glb"), PatchMesh{}, ShadingMesh{}, {}, {}).ok());
}

}  // namespace
}  // namespace radflux
