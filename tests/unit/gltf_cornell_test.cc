// The Cornell box as OBJ and as glTF: the same triangles in the same order give bit-identical
// per-patch radiosity. glTF stores positions as 32-bit floats and only triangles, so both
// files are written here from scenes/cornell_box.obj with its coordinates in tenths of a
// millimetre (integers, exact in float and in any OBJ parser) and every polygon fanned into
// triangles from its first vertex; the materials are the original MTL's (the glTF factors
// carry the very doubles the OBJ loader read). The textured variant gives every vertex
// texture coordinates on a half-unit grid (exact in float and in tinyobjloader's parser; OBJ's
// v is 1 - glTF's) and the white material a 4 x 4 texture (map_Kd / baseColorTexture).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "solver/output/default_view.h"
#include "solver/pipeline.h"
#include "solver/scene/gltf_loader.h"
#include "solver/scene/obj_loader.h"
#include "solver/solve/energy_balance.h"
#include "tests/source_path.h"
#include "tests/unit/cornell_picture.h"
#include "tests/unit/gltf_test_builder.h"
#include "tests/unit/texture_test_png.h"

namespace radflux {
namespace {

using testing::GltfBuilder;
using Json = nlohmann::json;

constexpr double kScale = 10;  // millimetres -> tenths of a millimetre

// The texture coordinates of a vertex at `p` (mm), glTF's (v = 0 at the image's top): a
// planar projection rounded to a half-unit grid.
std::array<double, 2> TexCoordOf(const Vec3& p) {
  return {std::round(2 * (p.x + p.z) / 150) / 2, std::round(2 * (p.y + p.z) / 150) / 2};
}

// A 4 x 4 texture: sRGB bytes varying by texel, opaque.
std::string Checker() {
  std::vector<unsigned char> rgba;
  for (int t = 0; t < 16; ++t) {
    for (int c = 0; c < 3; ++c) rgba.push_back(static_cast<unsigned char>(40 + 13 * t + 50 * c));
    rgba.push_back(255);
  }
  return testing::Png(4, 4, rgba);
}

std::string ReadFile(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// The original's faces fanned into triangles (v0, v[k], v[k + 1]), in order.
struct Fanned {
  std::vector<std::vector<uint32_t>> triangles;
  std::vector<size_t> face;  // the original face of each triangle
};

Fanned Fan(const Scene& scene) {
  Fanned fanned;
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const std::vector<uint32_t>& v = scene.faces[f].vertices;
    for (size_t k = 1; k + 1 < v.size(); ++k) {
      fanned.triangles.push_back({v[0], v[k], v[k + 1]});
      fanned.face.push_back(f);
    }
  }
  return fanned;
}

// The fanned scene as OBJ text (integer coordinates; materials from the MTL), with a
// texture coordinate per vertex when `textured`.
std::string FannedObj(const Scene& scene, const Fanned& fanned, bool textured = false) {
  std::string obj;
  for (const Vec3& p : scene.positions) {
    absl::StrAppend(&obj, "v ", std::lround(kScale * p.x), " ", std::lround(kScale * p.y), " ",
                    std::lround(kScale * p.z), "\n");
    if (textured) absl::StrAppend(&obj, "vt ", TexCoordOf(p)[0], " ", 1 - TexCoordOf(p)[1], "\n");
  }
  for (size_t t = 0; t < fanned.triangles.size(); ++t) {
    const Face& face = scene.faces[fanned.face[t]];
    absl::StrAppend(&obj, "o ", scene.objects[face.object], "\ng ", scene.groups[face.group],
                    "\nusemtl ", scene.materials[face.material].name, "\n");
    const auto& v = fanned.triangles[t];
    if (textured) {
      absl::StrAppend(&obj, "f ", v[0] + 1, "/", v[0] + 1, " ", v[1] + 1, "/", v[1] + 1, " ",
                      v[2] + 1, "/", v[2] + 1, "\n");
    } else {
      absl::StrAppend(&obj, "f ", v[0] + 1, " ", v[1] + 1, " ", v[2] + 1, "\n");
    }
  }
  return obj;
}

// emission = pi * L_e with L_e = factor * strength exactly: strength a power of two.
Json GltfMaterial(const Material& material) {
  Rgb radiance{};
  double largest = 0;
  for (int b = 0; b < kBands; ++b) {
    radiance[b] = material.emission[b] / std::numbers::pi;
    EXPECT_EQ(std::numbers::pi * radiance[b], material.emission[b]);  // L_e round-trips
    largest = std::max(largest, radiance[b]);
  }
  const double strength = largest > 1 ? std::exp2(std::ceil(std::log2(largest))) : 1;
  Json m = {
      {"name", material.name},
      {"pbrMetallicRoughness",
       {{"baseColorFactor",
         {material.reflectance[0], material.reflectance[1], material.reflectance[2], 1}},
        {"metallicFactor", 0}}},
      {"emissiveFactor", {radiance[0] / strength, radiance[1] / strength, radiance[2] / strength}}};
  if (strength != 1)
    m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = strength;
  return m;
}

// The fanned scene as glTF: one node and mesh per object, one primitive per run of
// triangles of one material, indexing the object's own float position accessor (the
// object's vertices, a contiguous range of the OBJ's, so that the glTF loader lists the
// same vertices in the same order).
GltfBuilder FannedGltf(const Scene& scene, const Fanned& fanned, bool textured = false) {
  GltfBuilder b;
  for (const Material& material : scene.materials) {
    Json m = GltfMaterial(material);
    if (textured && material.name == "white") {
      m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    }
    b.AddMaterial(m);
  }
  if (textured) {
    b.json()["images"] = {{{"bufferView", b.AddView(Checker())}, {"mimeType", "image/png"}}};
    b.json()["textures"] = {{{"source", 0}}};
  }
  std::vector<int> roots;
  uint32_t next_vertex = 0;
  for (size_t t = 0; t < fanned.triangles.size();) {
    const uint32_t object = scene.faces[fanned.face[t]].object;
    size_t end = t;
    uint32_t last_vertex = next_vertex;
    for (; end < fanned.triangles.size() && scene.faces[fanned.face[end]].object == object; ++end) {
      for (uint32_t v : fanned.triangles[end]) {
        EXPECT_GE(v, next_vertex) << "objects' vertices are not in order";
        last_vertex = std::max(last_vertex, v);
      }
    }
    std::vector<float> xyz, uv;
    for (uint32_t v = next_vertex; v <= last_vertex; ++v) {
      const Vec3& p = scene.positions[v];
      for (double c : {p.x, p.y, p.z}) xyz.push_back(static_cast<float>(std::lround(kScale * c)));
      for (double c : TexCoordOf(p)) uv.push_back(static_cast<float>(c));
    }
    const int positions = b.AddPositions(xyz);
    const int texcoords =
        textured ? b.AddAccessor(b.AddView(GltfBuilder::Bytes(uv)), 5126, uv.size() / 2, "VEC2")
                 : -1;
    std::vector<Json> primitives;
    while (t < end) {
      const uint32_t material = scene.faces[fanned.face[t]].material;
      std::vector<uint32_t> indices;
      for (; t < end && scene.faces[fanned.face[t]].material == material; ++t) {
        for (uint32_t v : fanned.triangles[t]) indices.push_back(v - next_vertex);
      }
      primitives.push_back(GltfBuilder::Primitive(positions, b.AddIndices(indices), 4, material));
      if (textured) primitives.back()["attributes"]["TEXCOORD_0"] = texcoords;
    }
    roots.push_back(
        b.AddNode({{"name", scene.objects[object]}, {"mesh", b.AddMesh("", primitives)}}));
    next_vertex = last_vertex + 1;
  }
  EXPECT_EQ(next_vertex, scene.positions.size());
  b.SetScene(roots);
  b.json()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  return b;
}

JobResult Solve(Scene scene) {
  JobOptions options;
  options.mesh.target_patches = 400;
  options.form_factors.rays = 64;
  options.solver.tolerance = 1e-6;
  absl::StatusOr<JobResult> result = RunJob(std::move(scene), options);
  EXPECT_TRUE(result.ok()) << result.status();
  return result.ok() ? *std::move(result) : JobResult{};
}

// Loads the fanned Cornell box as OBJ and as glTF (and GLB), textured or not, checks that
// they are the same scene to the bit and solve to bit-identical B; returns the OBJ's.
Scene ExpectObjAndGltfAgree(bool textured) {
  absl::StatusOr<Scene> original = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  EXPECT_TRUE(original.ok()) << original.status();
  if (!original.ok()) return {};
  for (const Vec3& p : original->positions) {  // on a 0.1 mm grid: the scaling is exact
    for (double c : {p.x, p.y, p.z}) EXPECT_NEAR(kScale * c, std::lround(kScale * c), 1e-9);
  }
  const Fanned fanned = Fan(*original);
  std::string mtl = ReadFile(testing::SourcePath("scenes/cornell_box.mtl"));
  if (textured) {
    const size_t white = mtl.find("newmtl white\n");
    EXPECT_NE(white, std::string::npos);
    mtl.insert(white + 13, "map_Kd checker.png\n");
  }
  const TextureReader read = [](const std::string& name) -> absl::StatusOr<std::string> {
    if (name == "checker.png") return Checker();
    return absl::NotFoundError("no such file");
  };
  absl::StatusOr<Scene> obj =
      LoadObjText(FannedObj(*original, fanned, textured), mtl, "cornell_triangles.obj", read);
  EXPECT_TRUE(obj.ok()) << obj.status();
  if (!obj.ok()) return {};
  const GltfBuilder gltf = FannedGltf(*original, fanned, textured);
  const JobResult reference = Solve(*obj);
  EXPECT_TRUE(reference.solve.converged);
  EXPECT_GE(reference.solve.radiosity.size(), 300u);  // a meshed scene, not one patch a face
  if (reference.solve.radiosity.empty()) return {};
  EXPECT_GT(reference.solve.radiosity[0][0], 0);  // the floor is lit
  for (const auto& [name, data] : {std::pair<std::string, std::string>{"cornell.gltf", gltf.Gltf()},
                                   {"cornell.glb", gltf.Glb()}}) {
    absl::StatusOr<Scene> loaded = LoadGltfData(data, name, {});
    EXPECT_TRUE(loaded.ok()) << loaded.status();
    if (!loaded.ok()) continue;
    // The same scene, to the bit: positions, triangles, materials.
    EXPECT_EQ(loaded->positions, obj->positions) << name;
    EXPECT_EQ(loaded->faces.size(), obj->faces.size()) << name;
    if (loaded->faces.size() != obj->faces.size()) continue;
    for (size_t f = 0; f < obj->faces.size(); ++f) {
      EXPECT_EQ(loaded->faces[f].vertices, obj->faces[f].vertices) << name << " face " << f;
      const Material& a = loaded->materials[loaded->faces[f].material];
      const Material& b = obj->materials[obj->faces[f].material];
      EXPECT_EQ(a.reflectance, b.reflectance) << name << " face " << f;
      EXPECT_EQ(a.emission, b.emission) << name << " face " << f;
      EXPECT_EQ(loaded->objects[loaded->faces[f].object], obj->objects[obj->faces[f].object]);
    }
    const JobResult result = Solve(*std::move(loaded));
    EXPECT_EQ(result.solve.radiosity.size(), reference.solve.radiosity.size()) << name;
    if (result.solve.radiosity.size() != reference.solve.radiosity.size()) continue;
    size_t differing = 0;
    for (size_t p = 0; p < reference.solve.radiosity.size(); ++p) {
      differing += result.solve.radiosity[p] != reference.solve.radiosity[p];
    }
    EXPECT_EQ(differing, 0u) << name << ": patches whose B differs in any bit";
    // And the glTF scene's solve conserves energy (the open front lets light escape), within
    // the tolerance that follows from its 64-ray rows' noise (at 400 patches the imbalance
    // runs 0.3-1.5% over seeds, with analytic or light-sampled lamp columns alike).
    const EnergyBalance balance =
        ComputeEnergyBalance(result.System(), result.solve.radiosity, {64, 64});
    EXPECT_TRUE(balance.Ok()) << name << " imbalance " << balance.RelativeImbalance()
                              << " tolerance " << balance.Tolerance();
  }
  return *std::move(obj);
}

TEST(GltfCornellBox, SameTrianglesAsObjAndAsGltfGiveBitIdenticalRadiosity) {
  ExpectObjAndGltfAgree(false);
}

TEST(GltfCornellBox, TexturedAsObjWithMapKdAndAsGltfGiveBitIdenticalRadiosity) {
  const Scene obj = ExpectObjAndGltfAgree(true);
  // The texture took effect: the white faces' reflectances differ from 0.75 and each other.
  std::set<Rgb> white;
  for (const Face& face : obj.faces) {
    if (obj.materials[face.material].name == "white")
      white.insert(obj.materials[face.material].reflectance);
  }
  EXPECT_GE(white.size(), 10u);
  EXPECT_EQ(white.count(Rgb{0.75, 0.75, 0.75}), 0u);
}

// The glTF export's default picture (`radflux solve cornell.glb --render` at the CLI's
// defaults) shows the lit box: the view in through its open side is lit in every pixel.
TEST(GltfCornellBox, TheGltfExportsDefaultPictureIsTheLitBox) {
  absl::StatusOr<Scene> original = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(original.ok()) << original.status();
  const testing::SolvedScene solved = testing::SolveDefaults(
      LoadGltfData(FannedGltf(*original, Fan(*original), false).Glb(), "cornell.glb", {}));
  ASSERT_FALSE(solved.vertex_radiosity.empty());
  EXPECT_TRUE(solved.result->solve.converged);
  Camera request;
  request.width = 64, request.height = 48;
  request.vertical_fov_degrees = 39.3077;  // the CLI's default
  const Camera camera = DefaultCamera(solved.job().mesh, *solved.job().caster,
                                      solved.result->solve.radiosity, request, Vec3{});
  EXPECT_EQ(testing::LitShare(testing::RenderSolved(solved, camera)), 1.0);
}

}  // namespace
}  // namespace radflux
