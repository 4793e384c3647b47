// glTF loading: hand-written files in, faces, transforms, windings and materials checked
// against what the glTF 2.0 spec says they mean.
#include "solver/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "solver/scene/load_scene.h"
#include "tests/unit/gltf_test_builder.h"

namespace radflux {
namespace {

using testing::GltfBuilder;
using Json = nlohmann::json;

// One triangle in the z = 0 plane, counter-clockwise seen from +z.
const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

absl::StatusOr<Scene> Load(const GltfBuilder& builder, const ImportOptions& options = {}) {
  return LoadGltfData(builder.Gltf(), "test.gltf", options);
}

// A builder with one node `node` (extra fields merged in) holding a one-primitive mesh.
GltfBuilder OneNode(const std::vector<float>& positions, const Json& node = Json::object(),
                    int mode = 4, const std::vector<uint32_t>& indices = {}) {
  GltfBuilder b;
  const int p = b.AddPositions(positions);
  const int i = indices.empty() ? -1 : b.AddIndices(indices);
  Json n = node;
  n["mesh"] = b.AddMesh("Chair", {GltfBuilder::Primitive(p, i, mode)});
  b.SetScene({b.AddNode(n)});
  return b;
}

Vec3 FaceNormal(const Scene& scene, size_t f) {
  return Normalize(PolygonNewellNormal(FacePolygon(scene, scene.faces[f])));
}

void ExpectNear(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(GltfLoader, OneTriangleKeepsPositionsWindingAndNames) {
  absl::StatusOr<Scene> scene = Load(OneNode(kTriangle, {{"name", "Seat"}}));
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->faces.size(), 1u);
  EXPECT_EQ(scene->source, "test.gltf");
  EXPECT_EQ(scene->files, std::vector<std::string>{"test.gltf"});
  const Face& face = scene->faces[0];
  EXPECT_EQ(face.source_line, 0);
  EXPECT_EQ(face.source_file, 0u);
  EXPECT_EQ(scene->objects[face.object], "Seat");
  EXPECT_EQ(scene->groups[face.group], "Chair");
  EXPECT_EQ(FacePolygon(*scene, face), (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
  // No material: glTF's default, white.
  EXPECT_EQ(scene->materials[face.material].name, "default");
  EXPECT_EQ(scene->materials[face.material].reflectance, (Rgb{1, 1, 1}));
  EXPECT_FALSE(scene->materials[face.material].two_sided);
}

TEST(GltfLoader, TranslationRotationScaleAndMatrix) {
  const double h = std::sqrt(0.5);
  // T * R * S: scale x by 2, rotate 90 degrees about z, then translate by (10, 20, 30).
  absl::StatusOr<Scene> trs = Load(
      OneNode(kTriangle,
              {{"scale", {2, 1, 1}}, {"rotation", {0, 0, h, h}}, {"translation", {10, 20, 30}}}));
  ASSERT_TRUE(trs.ok()) << trs.status();
  const std::vector<Vec3> expected = {{10, 20, 30}, {10, 22, 30}, {9, 20, 30}};
  for (int k = 0; k < 3; ++k) ExpectNear(trs->positions[trs->faces[0].vertices[k]], expected[k]);
  // The same transform as a column-major matrix.
  absl::StatusOr<Scene> matrix =
      Load(OneNode(kTriangle, {{"matrix", {0, 2, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 10, 20, 30, 1}}}));
  ASSERT_TRUE(matrix.ok()) << matrix.status();
  for (int k = 0; k < 3; ++k) {
    ExpectNear(matrix->positions[matrix->faces[0].vertices[k]], expected[k]);
  }
}

TEST(GltfLoader, NestedNodesComposeFromTheRootDown) {
  GltfBuilder b;
  const int mesh = b.AddMesh("Leaf", {GltfBuilder::Primitive(b.AddPositions(kTriangle))});
  // grandchild: mesh, translated by (1, 0, 0); child: scaled by 3; root: translated by z 5.
  const int grandchild = b.AddNode({{"mesh", mesh}, {"translation", {1, 0, 0}}});
  const int child = b.AddNode({{"children", {grandchild}}, {"scale", {3, 3, 3}}});
  b.SetScene({b.AddNode({{"children", {child}}, {"translation", {0, 0, 5}}})});
  absl::StatusOr<Scene> scene = Load(b);
  ASSERT_TRUE(scene.ok()) << scene.status();
  const std::vector<Vec3> expected = {{3, 0, 5}, {6, 0, 5}, {3, 3, 5}};
  for (int k = 0; k < 3; ++k)
    ExpectNear(scene->positions[scene->faces[0].vertices[k]], expected[k]);
  EXPECT_EQ(scene->objects[scene->faces[0].object], "Leaf");  // unnamed node: its mesh's name
}

TEST(GltfLoader, OneMeshUnderTwoNodesIsTwoInstances) {
  GltfBuilder b;
  const int mesh = b.AddMesh("", {GltfBuilder::Primitive(b.AddPositions(kTriangle))});
  b.SetScene({b.AddNode({{"mesh", mesh}, {"name", "a"}}),
              b.AddNode({{"mesh", mesh}, {"translation", {0, 0, 2}}})});
  absl::StatusOr<Scene> scene = Load(b);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->faces.size(), 2u);
  EXPECT_EQ(scene->positions[scene->faces[1].vertices[0]], (Vec3{0, 0, 2}));
  EXPECT_EQ(scene->objects[scene->faces[0].object], "a");
  EXPECT_EQ(scene->objects[scene->faces[1].object], "node 1");
  EXPECT_EQ(scene->groups[scene->faces[1].group], "mesh 0");
}

// A strip of 5 vertices along x in the z = 0 plane: 0 2 4 at y = 0, 1 3 at y = 1.
const std::vector<float> kStrip = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0};

std::vector<std::vector<uint32_t>> Triangles(const Scene& scene) {
  std::vector<std::vector<uint32_t>> triangles;
  for (const Face& face : scene.faces) triangles.push_back(face.vertices);
  return triangles;
}

TEST(GltfLoader, StripsAndFansGiveTheSpecsTriangles) {
  // Strip vertices 0 1 2 3 4: (0 1 2), (1 3 2), (2 3 4), all facing the same way.
  absl::StatusOr<Scene> strip = Load(OneNode(kStrip, {}, 5));
  ASSERT_TRUE(strip.ok()) << strip.status();
  EXPECT_EQ(Triangles(*strip),
            (std::vector<std::vector<uint32_t>>{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}}));
  for (size_t f = 0; f < 3; ++f) ExpectNear(FaceNormal(*strip, f), {0, 0, -1});
  // Fan around the centre of a square, counter-clockwise from +z: (1 2 0), (2 3 0), (3 4 0).
  const std::vector<float> fan = {0, 0, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, -1, -1, 0};
  absl::StatusOr<Scene> fanned = Load(OneNode(fan, {}, 6));
  ASSERT_TRUE(fanned.ok()) << fanned.status();
  EXPECT_EQ(Triangles(*fanned),
            (std::vector<std::vector<uint32_t>>{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}}));
  for (size_t f = 0; f < 3; ++f) ExpectNear(FaceNormal(*fanned, f), {0, 0, 1});
}

TEST(GltfLoader, IndexedStripWithRestartDropsTheRepeatedVertexTriangles) {
  // Indices 0 1 2 2 3 3 4 by the strip rule: (0 1 2), then (1 2 2), (2 2 3), (2 3 3) and
  // (3 3 4), each repeating a vertex: one triangle kept, four dropped.
  absl::StatusOr<Scene> scene = Load(OneNode(kStrip, {}, 5, {0, 1, 2, 2, 3, 3, 4}));
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(Triangles(*scene), (std::vector<std::vector<uint32_t>>{{0, 1, 2}}));
  ASSERT_EQ(scene->import_log.fixups().size(), 1u);
  EXPECT_EQ(scene->import_log.fixups()[0].kind, "gltf_repeated_vertex_dropped");
  EXPECT_EQ(scene->import_log.fixups()[0].count, 4u);
  EXPECT_EQ(scene->import_log.fixups()[0].first, "test.gltf: mesh 'Chair' primitive 0 triangle 1");
  ImportOptions strict;
  strict.strict = true;
  absl::StatusOr<Scene> refused = Load(OneNode(kStrip, {}, 5, {0, 1, 2, 2, 3, 3, 4}), strict);
  EXPECT_EQ(refused.status().message(),
            "test.gltf: mesh 'Chair' primitive 0: triangle 1 repeats a vertex (zero area)");
}

TEST(GltfLoader, EveryIndexComponentTypeGivesTheSameFaces) {
  for (int type : {5121, 5123, 5125}) {
    GltfBuilder b;
    const int p = b.AddPositions(kStrip);
    const int i = b.AddIndices({0, 2, 1, 2, 4, 3}, type);
    b.SetScene({b.AddNode({{"mesh", b.AddMesh("m", {GltfBuilder::Primitive(p, i)})}})});
    absl::StatusOr<Scene> scene = Load(b);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(Triangles(*scene), (std::vector<std::vector<uint32_t>>{{0, 2, 1}, {2, 4, 3}}))
        << "componentType " << type;
  }
}

TEST(GltfLoader, InterleavedPositionsWithByteStride) {
  // position, then a 3-float normal, per vertex: stride 24, positions at offset 0.
  std::vector<float> interleaved;
  for (size_t v = 0; v < 3; ++v) {
    interleaved.insert(interleaved.end(),
                       {kTriangle[3 * v], kTriangle[3 * v + 1], kTriangle[3 * v + 2]});
    interleaved.insert(interleaved.end(), {99, 99, 99});
  }
  GltfBuilder b;
  const int p = b.AddAccessor(b.AddView(GltfBuilder::Bytes(interleaved), 24), 5126, 3, "VEC3");
  b.SetScene({b.AddNode({{"mesh", b.AddMesh("m", {GltfBuilder::Primitive(p)})}})});
  absl::StatusOr<Scene> scene = Load(b);
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(FacePolygon(*scene, scene->faces[0]),
            (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
}

TEST(GltfLoader, QuantizedPositions) {
  // KHR_mesh_quantization: normalized shorts map 32767 to 1 and -32768 to -1; plain unsigned
  // bytes are their values.
  GltfBuilder b;
  const int shorts = b.AddAccessor(b.AddView(GltfBuilder::Bytes(std::vector<int16_t>{
                                       0, 0, 0, 32767, 0, 0, 0, -32768, 0, 0, 0, 0})),
                                   5122, 3, "VEC3");
  b.json()["accessors"][shorts]["normalized"] = true;
  const int bytes = b.AddAccessor(
      b.AddView(GltfBuilder::Bytes(std::vector<uint8_t>{0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0})), 5121,
      3, "VEC3");
  b.json()["bufferViews"][1]["byteStride"] = 4;  // each element padded to 4 bytes
  b.SetScene({b.AddNode({{"mesh", b.AddMesh("m", {GltfBuilder::Primitive(shorts),
                                                  GltfBuilder::Primitive(bytes)})}})});
  b.json()["extensionsUsed"] = b.json()["extensionsRequired"] = {"KHR_mesh_quantization"};
  absl::StatusOr<Scene> scene = Load(b);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->faces.size(), 2u);
  EXPECT_EQ(FacePolygon(*scene, scene->faces[0]),
            (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, -1, 0}}));
  EXPECT_EQ(FacePolygon(*scene, scene->faces[1]),
            (std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}));
}

TEST(GltfLoader, MirroringTransformKeepsTheFrontFacingTheSameWay) {
  // Mirroring x (and, nested, a second mirror that cancels it) keeps the triangle facing +z,
  // as the spec's winding rule for a negative determinant requires.
  absl::StatusOr<Scene> mirrored = Load(OneNode(kTriangle, {{"scale", {-1, 1, 1}}}));
  ASSERT_TRUE(mirrored.ok()) << mirrored.status();
  ExpectNear(FaceNormal(*mirrored, 0), {0, 0, 1});
  EXPECT_EQ(mirrored->positions[mirrored->faces[0].vertices[1]], (Vec3{0, 1, 0}));
  GltfBuilder b;
  const int mesh = b.AddMesh("m", {GltfBuilder::Primitive(b.AddPositions(kTriangle))});
  const int child = b.AddNode({{"mesh", mesh}, {"scale", {1, -1, 1}}});
  b.SetScene({b.AddNode({{"children", {child}}, {"scale", {-1, 1, 1}}})});
  absl::StatusOr<Scene> twice = Load(b);
  ASSERT_TRUE(twice.ok()) << twice.status();
  ExpectNear(FaceNormal(*twice, 0), {0, 0, 1});
  EXPECT_EQ(twice->positions[twice->faces[0].vertices[1]], (Vec3{-1, 0, 0}));
}

TEST(GltfLoader, MaterialsFactorsEmissiveStrengthAndDoubleSided) {
  GltfBuilder b;
  const int lamp = b.AddMaterial(
      {{"name", "lamp"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 0.125, 1}}, {"metallicFactor", 0}}},
       {"emissiveFactor", {1, 0.5, 0.25}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8}}}}}});
  const int leaf = b.AddMaterial({{"pbrMetallicRoughness", {{"metallicFactor", 0}}},
                                  {"emissiveFactor", {0.5, 0, 0}},
                                  {"doubleSided", true}});
  const int p = b.AddPositions(kTriangle);
  b.SetScene({b.AddNode({{"mesh", b.AddMesh("m", {GltfBuilder::Primitive(p, -1, 4, lamp),
                                                  GltfBuilder::Primitive(p, -1, 4, leaf)})}})});
  b.json()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  absl::StatusOr<Scene> scene = Load(b);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->materials.size(), 2u);
  const Material& a = scene->materials[scene->faces[0].material];
  EXPECT_EQ(a.name, "lamp");
  EXPECT_EQ(a.reflectance, (Rgb{0.5, 0.25, 0.125}));
  EXPECT_EQ(a.emission, (Rgb{8 * std::numbers::pi, 4 * std::numbers::pi, 2 * std::numbers::pi}));
  EXPECT_FALSE(a.two_sided);
  const Material& c = scene->materials[scene->faces[1].material];
  EXPECT_EQ(c.name, "material 1");
  EXPECT_EQ(c.reflectance, (Rgb{1, 1, 1}));                    // the default base colour
  EXPECT_EQ(c.emission, (Rgb{0.5 * std::numbers::pi, 0, 0}));  // strength 1 when absent
  EXPECT_TRUE(c.two_sided);
  EXPECT_EQ(scene->groups[scene->faces[1].group], "m primitive 1");
  EXPECT_TRUE(scene->import_log.empty());  // no textures, no metal
}

TEST(GltfLoader, PointsAndLinesAreSkippedAndCounted) {
  GltfBuilder b;
  const int p = b.AddPositions(kTriangle);
  b.SetScene({b.AddNode(
      {{"mesh", b.AddMesh("m", {GltfBuilder::Primitive(p, -1, 0), GltfBuilder::Primitive(p, -1, 1),
                                GltfBuilder::Primitive(p, -1, 4)})}})});
  absl::StatusOr<Scene> scene = Load(b);
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->faces.size(), 1u);
  ASSERT_FALSE(scene->import_log.empty());
  EXPECT_EQ(scene->import_log.fixups()[0].kind, "gltf_points_lines_skipped");
  EXPECT_EQ(scene->import_log.fixups()[0].count, 2u);
}

TEST(GltfLoader, DefaultSceneOnly) {
  GltfBuilder b;
  const int mesh = b.AddMesh("m", {GltfBuilder::Primitive(b.AddPositions(kTriangle))});
  const int first = b.AddNode({{"mesh", mesh}, {"name", "in scene 0"}});
  const int second = b.AddNode({{"mesh", mesh}, {"name", "in scene 1"}});
  b.json()["scenes"] = {{{"nodes", {first}}}, {{"nodes", {second}}}};
  b.json()["scene"] = 1;
  absl::StatusOr<Scene> scene = Load(b);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->faces.size(), 1u);
  EXPECT_EQ(scene->objects[scene->faces[0].object], "in scene 1");
}

TEST(GltfLoader, GlbAndExternalBinAndLoadSceneGiveTheSameScene) {
  const GltfBuilder b = OneNode(kStrip, {{"name", "n"}}, 5);
  absl::StatusOr<Scene> embedded = Load(b);
  ASSERT_TRUE(embedded.ok()) << embedded.status();
  absl::StatusOr<Scene> glb = LoadGltfData(b.Glb(), "test.glb", {});
  ASSERT_TRUE(glb.ok()) << glb.status();
  EXPECT_EQ(glb->positions, embedded->positions);
  EXPECT_EQ(Triangles(*glb), Triangles(*embedded));
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "gltf_files";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.gltf") << b.Gltf("scene data.bin");
  std::ofstream(dir / "scene data.bin", std::ios::binary) << b.bin();
  std::ofstream(dir / "scene.GLB", std::ios::binary) << b.Glb();
  for (const char* file : {"scene.gltf", "scene.GLB"}) {
    absl::StatusOr<Scene> loaded = LoadScene((dir / file).string(), {});
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    EXPECT_EQ(loaded->source, (dir / file).string());
    EXPECT_EQ(loaded->positions, embedded->positions);
    EXPECT_EQ(Triangles(*loaded), Triangles(*embedded));
  }
  // From memory, the .bin comes from the bundle of files (an upload), keyed by its URI.
  absl::StatusOr<Scene> bundled = LoadGltfData(b.Gltf("bin/scene%20data.bin"), "up.gltf", {},
                                               {{"bin/scene data.bin", b.bin()}});
  ASSERT_TRUE(bundled.ok()) << bundled.status();
  EXPECT_EQ(bundled->positions, embedded->positions);
  EXPECT_EQ(Triangles(*bundled), Triangles(*embedded));
  // Not in the bundle, or reached through "..": not read (and never from disk).
  for (const char* uri : {"scene data.bin", "bin/../bin/scene data.bin"}) {
    absl::StatusOr<Scene> missing =
        LoadGltfData(b.Gltf(uri), "up.gltf", {}, {{"bin/scene data.bin", b.bin()}});
    EXPECT_EQ(missing.status().code(), absl::StatusCode::kInvalidArgument) << uri;
    EXPECT_NE(missing.status().message().find(uri), std::string::npos) << missing.status();
  }
}

}  // namespace
}  // namespace radflux
