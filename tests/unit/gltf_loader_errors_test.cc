// Malformed glTF gives one clear line naming the file (and the mesh and primitive when the
// problem is in one), never a crash: each case here is a way a file can be wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "solver/scene/gltf_loader.h"
#include "tests/unit/gltf_test_builder.h"

namespace radflux {
namespace {

using testing::GltfBuilder;
using Json = nlohmann::json;

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

// A valid one-triangle file (mesh "Chair", indexed) that each test then breaks.
GltfBuilder Valid() {
  GltfBuilder b;
  const int p = b.AddPositions(kTriangle);
  const int i = b.AddIndices({0, 1, 2});
  b.SetScene({b.AddNode({{"mesh", b.AddMesh("Chair", {GltfBuilder::Primitive(p, i)})}})});
  return b;
}

std::string Message(const std::string& data, const std::string& name = "bad.gltf") {
  absl::StatusOr<Scene> scene = LoadGltfData(data, name, {});
  EXPECT_EQ(scene.status().code(), absl::StatusCode::kInvalidArgument) << scene.status();
  const std::string message(scene.status().message());
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
  return message;
}

TEST(GltfLoaderErrors, ValidFileLoads) {
  EXPECT_TRUE(LoadGltfData(Valid().Gltf(), "ok.gltf", {}).ok());
}

TEST(GltfLoaderErrors, IndexOutOfRangeNamesMeshAndPrimitive) {
  GltfBuilder b = Valid();
  b.json()["accessors"][1]["bufferView"] =
      b.AddView(GltfBuilder::Bytes(std::vector<uint32_t>{0, 1, 7}));
  EXPECT_EQ(Message(b.Gltf()),
            "bad.gltf: mesh 'Chair' primitive 0: index 7 out of range (3 vertices)");
}

TEST(GltfLoaderErrors, AccessorPastTheEndOfItsView) {
  GltfBuilder b = Valid();
  b.json()["accessors"][0]["count"] = 4;
  EXPECT_EQ(
      Message(b.Gltf()),
      "bad.gltf: mesh 'Chair' primitive 0: accessor 0: reaches past the end of its bufferView");
  b.json()["accessors"][0]["count"] = uint64_t{1} << 62;  // stride * count overflows 64 bits
  EXPECT_EQ(
      Message(b.Gltf()),
      "bad.gltf: mesh 'Chair' primitive 0: accessor 0: reaches past the end of its bufferView");
}

TEST(GltfLoaderErrors, ViewPastTheEndOfItsBuffer) {
  GltfBuilder b = Valid();
  b.json()["bufferViews"][0]["byteOffset"] = 40;
  EXPECT_NE(Message(b.Gltf()).find("past the end of its buffer"), std::string::npos);
}

TEST(GltfLoaderErrors, ByteStrideSmallerThanAnElement) {
  GltfBuilder b = Valid();
  b.json()["bufferViews"][0]["byteStride"] = 4;
  EXPECT_NE(Message(b.Gltf()).find("byteStride is smaller than an element"), std::string::npos);
}

TEST(GltfLoaderErrors, WrongTypesAndMissingAccessors) {
  GltfBuilder b = Valid();
  b.json()["accessors"][0]["type"] = "VEC2";
  EXPECT_NE(Message(b.Gltf()).find("expected 3 components"), std::string::npos);
  b = Valid();
  b.json()["accessors"][1]["componentType"] = 5126;  // float indices
  EXPECT_NE(Message(b.Gltf()).find("indices must be unsigned"), std::string::npos);
  b = Valid();
  b.json()["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
  EXPECT_NE(Message(b.Gltf()).find("accessor 9 does not exist"), std::string::npos);
  b = Valid();
  b.json()["meshes"][0]["primitives"][0]["attributes"].erase("POSITION");
  b.json()["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 0;
  EXPECT_EQ(Message(b.Gltf()), "bad.gltf: mesh 'Chair' primitive 0: has no POSITION attribute");
}

TEST(GltfLoaderErrors, SparseAccessorsAreRefused) {
  GltfBuilder b = Valid();
  const int indices = b.AddView(GltfBuilder::Bytes(std::vector<uint32_t>{1}));
  const int values = b.AddView(GltfBuilder::Bytes(std::vector<float>{5, 5, 5}));
  b.json()["accessors"][0]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", indices}, {"componentType", 5125}}},
      {"values", {{"bufferView", values}}}};
  EXPECT_EQ(Message(b.Gltf()),
            "bad.gltf: mesh 'Chair' primitive 0: accessor 0: sparse accessors are not supported");
}

TEST(GltfLoaderErrors, NodeCyclesAndBadReferences) {
  GltfBuilder b = Valid();
  b.json()["nodes"][0]["children"] = {0};
  EXPECT_NE(Message(b.Gltf()).find("node 0 is reached twice"), std::string::npos);
  b = Valid();
  b.json()["scenes"][0]["nodes"] = {5};
  EXPECT_EQ(Message(b.Gltf()), "bad.gltf: node 5 does not exist");
  b = Valid();
  b.json()["scene"] = 3;
  EXPECT_EQ(Message(b.Gltf()), "bad.gltf: default scene 3 does not exist");
  b = Valid();
  b.json()["meshes"][0]["primitives"][0]["material"] = 2;
  EXPECT_EQ(Message(b.Gltf()), "bad.gltf: mesh 'Chair' primitive 0: material 2 does not exist");
  b = Valid();
  b.json()["meshes"][0]["primitives"][0]["mode"] = 9;
  EXPECT_EQ(Message(b.Gltf()), "bad.gltf: mesh 'Chair' primitive 0: unknown mode 9");
}

TEST(GltfLoaderErrors, BadTransformsAndMaterials) {
  GltfBuilder b = Valid();
  b.json()["nodes"][0]["matrix"] = {1, 0, 0, 1};
  EXPECT_EQ(Message(b.Gltf()), "bad.gltf: unnamed node: matrix must have 16 numbers");
  b = Valid();
  b.json()["nodes"][0]["rotation"] = {0, 0, 0, 0};
  b.json()["nodes"][0]["name"] = "Arm";
  EXPECT_EQ(Message(b.Gltf()),
            "bad.gltf: node 'Arm': rotation quaternion has zero (or overflowing) length");
  b = Valid();
  b.json()["materials"] = {{{"name", "m"}, {"emissiveFactor", {1, 1}}}};
  EXPECT_NE(Message(b.Gltf()).find("emissiveFactor"), std::string::npos);  // tinygltf's check
  b = Valid();
  b.json()["materials"] = {
      {{"name", "m"},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", -1}}}}}}};
  EXPECT_NE(Message(b.Gltf()).find("emissiveStrength must be finite and >= 0"), std::string::npos);
}

TEST(GltfLoaderErrors, NonFinitePositions) {
  GltfBuilder b = Valid();
  b.json()["accessors"][0]["bufferView"] =
      b.AddView(GltfBuilder::Bytes(std::vector<float>{0, 0, 0, 1, 0, 0, 0, std::nanf(""), 0}));
  EXPECT_EQ(Message(b.Gltf()),
            "bad.gltf: mesh 'Chair' primitive 0: vertex 2 has a NaN or infinite coordinate");
}

TEST(GltfLoaderErrors, RequiredExtensionNotRead) {
  GltfBuilder b = Valid();
  b.json()["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.json()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_EQ(Message(b.Gltf()),
            "bad.gltf: requires glTF extension 'KHR_draco_mesh_compression', which radflux does "
            "not read");
  b.json()["extensionsUsed"] = b.json()["extensionsRequired"] = {"EXT_meshopt_compression"};
  EXPECT_NE(Message(b.Gltf()).find("'EXT_meshopt_compression'"), std::string::npos);
  // Material extensions and quantized attributes change nothing a diffuse solve reads.
  b.json()["extensionsUsed"] = b.json()["extensionsRequired"] = {
      "KHR_materials_clearcoat", "KHR_mesh_quantization", "KHR_texture_transform"};
  EXPECT_TRUE(LoadGltfData(b.Gltf(), "ok.gltf", {}).ok());
}

TEST(GltfLoaderErrors, UnparsableInput) {
  EXPECT_NE(Message("{ not json").find("cannot parse glTF"), std::string::npos);
  EXPECT_NE(Message("").find("cannot parse glTF"), std::string::npos);
  EXPECT_NE(Message(R"({"asset": {}})").find("cannot parse glTF"), std::string::npos);
  const std::string glb = Valid().Glb();
  EXPECT_NE(Message(glb.substr(0, 30), "bad.glb").find("cannot parse glTF"), std::string::npos);
  EXPECT_NE(Message(glb.substr(0, glb.size() - 8), "bad.glb").find("cannot parse glTF"),
            std::string::npos);
  // A buffer in an external file cannot be read when loading from memory.
  EXPECT_NE(Message(Valid().Gltf("data.bin")).find("data.bin"), std::string::npos);
}

TEST(GltfLoaderErrors, TooManyTrianglesAreRefusedBeforeMemoryRunsOut) {
  // One mesh of 65,536 triangles under 257 nodes draws 16,842,752 > kMaxGltfTriangles.
  GltfBuilder b;
  const int p = b.AddPositions(kTriangle);
  const int i = b.AddIndices(std::vector<uint32_t>(3 * 65536, 0), 5121);
  const int mesh = b.AddMesh("Grass", {GltfBuilder::Primitive(p, i)});
  std::vector<int> roots;
  for (int n = 0; n < 257; ++n) roots.push_back(b.AddNode({{"mesh", mesh}}));
  b.SetScene(roots);
  EXPECT_EQ(Message(b.Glb(), "big.glb"),
            "big.glb: mesh 'Grass' primitive 0: the scene has more than 16777216 triangles");
}

// A crash of the fuzz target (on a hand-made input; libFuzzer's inputs were too short to
// reach it): tinygltf parses nested JSON values recursively, and 200,000 nested arrays in
// "extras" overflowed the stack.
TEST(GltfLoaderErrors, DeeplyNestedJsonIsRefusedNotRecursedInto) {
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  EXPECT_EQ(Message(R"({"asset": {"version": "2.0"}, "extras": )" + deep + "}"),
            "bad.gltf: cannot parse glTF: JSON nested deeper than 64 levels");
  GltfBuilder b = Valid();
  b.json()["extras"] = Json::parse(std::string(100, '[') + std::string(100, ']'));
  EXPECT_EQ(Message(b.Glb(), "bad.glb"),
            "bad.glb: cannot parse glTF: JSON nested deeper than 64 levels");
  // Brackets inside strings do not count; 60 levels of real nesting are fine.
  b = Valid();
  b.json()["extras"] = {{"text", std::string(1000, '[') + "\\\"["},
                        {"deep", Json::parse(std::string(60, '[') + std::string(60, ']'))}};
  EXPECT_TRUE(LoadGltfData(b.Gltf(), "ok.gltf", {}).ok());
}

TEST(GltfLoaderErrors, ExternalFilesOutsideTheScenesDirectoryAreNotRead) {
  EXPECT_EQ(LoadGltfFile("/nonexistent/x.gltf", {}).status().code(), absl::StatusCode::kNotFound);
  const std::string dir = ::testing::TempDir();
  const std::string path = dir + "/escape.gltf";
  std::ofstream(path) << Valid().Gltf("../escape.bin");
  std::ofstream(dir + "/../escape.bin", std::ios::binary) << Valid().bin();
  absl::StatusOr<Scene> scene = LoadGltfFile(path, {});
  EXPECT_EQ(scene.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(scene.status().message().find("escape.bin"), std::string::npos) << scene.status();
}

}  // namespace
}  // namespace radflux
