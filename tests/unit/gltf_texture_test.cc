// glTF textures (solver/scene/gltf_textures.h, face_textures.h): a face's reflectance is
// baseColorFactor times the mean of baseColorTexture over the face's footprint (sRGB decoded;
// glTF's v = 0 is the image's top row), its emission emissiveFactor x emissiveStrength x the
// emissive texture's mean; under alphaMode MASK a texel is opaque when its alpha (times the
// factor's) reaches alphaCutoff, under BLEND its alpha is its opacity, under OPAQUE alpha is
// ignored; a face under 1/255 opaque is dropped, one partly transparent keeps its mean alpha
// as its opacity and is counted. KHR_texture_transform maps the coordinates, the sampler's
// wrap modes continue the image outside [0, 1]; images come from data URIs, buffer views or
// files (found ignoring case).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "absl/strings/escaping.h"
#include "solver/scene/gltf_loader.h"
#include "tests/unit/gltf_test_builder.h"
#include "tests/unit/texture_test_png.h"

namespace radflux {
namespace {

using testing::GltfBuilder;
using testing::Linear;
using testing::Png;
using Json = nlohmann::json;

// Top-left, top-right, bottom-left, bottom-right: sRGB bytes and alpha 255, 0, 128, 64.
const std::vector<unsigned char> kTexels = {128, 64, 255, 255, 0,   255, 0,   0,
                                            10,  20, 30,  128, 200, 100, 50, 64};

// The linear value of channel `c` of texel `t` (0..3 as in kTexels).
double Texel(int t, int c) { return Linear(kTexels[4 * t + c]); }

// One unit quad in z = 0 (two triangles: 0 1 2 and 0 2 3) named "quad", texture coordinates
// `uv` (u, v per corner), material `material`; the image is `image` (JSON: a data URI of
// the 2 x 2 PNG unless the test says otherwise).
GltfBuilder Quad(const std::vector<float>& uv, const Json& material,
                 const Json& image = Json()) {
  GltfBuilder b;
  const int positions = b.AddPositions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  const int texcoords = b.AddAccessor(b.AddView(GltfBuilder::Bytes(uv)), 5126, 4, "VEC2");
  Json primitive = GltfBuilder::Primitive(positions, b.AddIndices({0, 1, 2, 0, 2, 3}), 4,
                                          b.AddMaterial(material));
  primitive["attributes"]["TEXCOORD_0"] = texcoords;
  b.SetScene({b.AddNode({{"name", "quad"}, {"mesh", b.AddMesh("", {primitive})}})});
  b.json()["images"] = {image.is_null() ? Json{{"uri", "data:image/png;base64," +
                                                         absl::Base64Escape(Png(2, 2, kTexels))}}
                                        : image};
  b.json()["textures"] = {{{"source", 0}}};
  return b;
}

// A material with base colour factor `factor` and the texture as its base colour texture.
Json BaseColour(const std::vector<double>& factor, const std::string& alpha_mode = "OPAQUE") {
  return {{"pbrMetallicRoughness",
           {{"baseColorFactor", factor},
            {"baseColorTexture", {{"index", 0}}},
            {"metallicFactor", 0}}},
          {"alphaMode", alpha_mode}};
}

// The corners of the quad over texel t of the 2 x 2 image (glTF's v runs down).
std::vector<float> OverTexel(int t) {
  const float u = (t % 2) * 0.5f, v = (t / 2) * 0.5f;
  return {u, v, u + .5f, v, u + .5f, v + .5f, u, v + .5f};
}

Scene Load(const GltfBuilder& b, const std::map<std::string, std::string>& files = {}) {
  absl::StatusOr<Scene> scene = LoadGltfData(b.Gltf(), "q.gltf", {}, files);
  EXPECT_TRUE(scene.ok()) << scene.status();
  return scene.ok() ? *std::move(scene) : Scene{};
}

const Material& MaterialOf(const Scene& s, size_t f) { return s.materials[s.faces[f].material]; }

std::vector<std::string> Lines(const Scene& s) { return s.import_log.Lines(); }

TEST(GltfTextures, AQuadOverOneTexelTakesThatTexelTimesTheBaseColourFactor) {
  const Scene s = Load(Quad(OverTexel(0), BaseColour({0.8, 0.6, 0.4, 1})));
  ASSERT_EQ(s.faces.size(), 2u);
  for (size_t f = 0; f < 2; ++f) {
    const Rgb rho = MaterialOf(s, f).reflectance;
    EXPECT_NEAR(rho[0], 0.8 * Texel(0, 0), 1e-12);
    EXPECT_NEAR(rho[1], 0.6 * Texel(0, 1), 1e-12);
    EXPECT_NEAR(rho[2], 0.4 * Texel(0, 2), 1e-12);
  }
  EXPECT_EQ(Lines(s), std::vector<std::string>{
                          "import: 2 faces took their reflectance from textures "
                          "(baseColorTexture) (first at q.gltf (face 0 of object 'quad'))"});
}

TEST(GltfTextures, EachTriangleTakesTheMeanOverItsOwnFootprint) {
  // The quad over the top row: triangle 0 1 2 covers a quarter of the top-left texel's area
  // and three quarters of the top-right's; triangle 0 2 3 the other way round.
  const Scene s = Load(Quad({0, 0, 1, 0, 1, .5f, 0, .5f}, BaseColour({1, 1, 1, 1})));
  ASSERT_EQ(s.faces.size(), 2u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(MaterialOf(s, 0).reflectance[c], .25 * Texel(0, c) + .75 * Texel(1, c), 1e-12);
    EXPECT_NEAR(MaterialOf(s, 1).reflectance[c], .75 * Texel(0, c) + .25 * Texel(1, c), 1e-12);
  }
}

TEST(GltfTextures, EmissionIsFactorTimesStrengthTimesTheEmissiveTexturesMean) {
  Json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {.5, .5, .5, 1}}, {"metallicFactor", 0}}},
                   {"emissiveFactor", {.5, 1, 2}},
                   {"emissiveTexture", {{"index", 0}}},
                   {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3}}}}}};
  GltfBuilder b = Quad(OverTexel(2), material);
  b.json()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  const Scene s = Load(b);
  ASSERT_EQ(s.faces.size(), 2u);
  const double factor[3] = {.5, 1, 2};
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(MaterialOf(s, 0).emission[c], std::numbers::pi * factor[c] * 3 * Texel(2, c),
                1e-12);
    EXPECT_EQ(MaterialOf(s, 0).reflectance[c], .5) << "no base colour texture";
  }
  EXPECT_EQ(Lines(s).front(),
            "import: 2 faces took their emission from textures (emissiveTexture) (first at "
            "q.gltf (face 0 of object 'quad'))");
}

TEST(GltfTextures, MaskDropsFacesWhoseTexelsAreBelowTheCutoff) {
  // Top-right texel: alpha 0. Both triangles over it go, with one line.
  Scene s = Load(Quad(OverTexel(1), BaseColour({1, 1, 1, 1}, "MASK")));
  EXPECT_EQ(s.faces.size(), 0u);
  EXPECT_EQ(Lines(s), std::vector<std::string>{
                          "import: 2 faces transparent (mean alpha < 1/255) in their alpha "
                          "texture (baseColor alpha) dropped (first at q.gltf (face 0 of object "
                          "'quad'))"});
  // Bottom-left texel: alpha 128/255 = 0.502. Cut out under MASK with alphaCutoff 0.6; kept
  // at that opacity (and counted as partly transparent) under BLEND; kept opaque and
  // silently under OPAQUE.
  Json mask = BaseColour({1, 1, 1, 1}, "MASK");
  mask["alphaCutoff"] = 0.6;
  EXPECT_EQ(Load(Quad(OverTexel(2), mask)).faces.size(), 0u);
  mask["alphaCutoff"] = 0.5;
  EXPECT_EQ(Load(Quad(OverTexel(2), mask)).faces.size(), 2u) << "0.502 >= 0.5: opaque";
  s = Load(Quad(OverTexel(2), BaseColour({1, 1, 1, 1}, "BLEND")));
  EXPECT_EQ(s.faces.size(), 2u);
  EXPECT_NEAR(MaterialOf(s, 0).opacity, 128 / 255.0, 1e-7);
  ASSERT_EQ(Lines(s).size(), 2u);
  EXPECT_EQ(Lines(s)[0],
            "import: 2 faces partly transparent (mean alpha in [1/255, 1)) in their alpha "
            "texture (baseColor alpha) let the transparent fraction through (first at q.gltf "
            "(face 0 of object 'quad'))");
  s = Load(Quad(OverTexel(1), BaseColour({1, 1, 1, 1}, "OPAQUE")));
  EXPECT_EQ(s.faces.size(), 2u) << "OPAQUE ignores alpha";
  EXPECT_EQ(MaterialOf(s, 0).opacity, 1);
  // The factor's alpha scales the texels' before the cutoff: 0.502 x 0.9 < 0.5.
  EXPECT_EQ(Load(Quad(OverTexel(2), BaseColour({1, 1, 1, .9}, "MASK"))).faces.size(), 0u);
}

TEST(GltfTextures, AFacePartlyOverACutOutTexelIsAsOpaqueAsItsOpaqueFraction) {
  // The top row under MASK: triangle 0 1 2 is 1/4 over the opaque top-left texel (opacity
  // 1/4), triangle 0 2 3 3/4 (opacity 3/4); each reflects the mean over all of it.
  const Scene s = Load(Quad({0, 0, 1, 0, 1, .5f, 0, .5f}, BaseColour({1, 1, 1, 1}, "MASK")));
  ASSERT_EQ(s.faces.size(), 2u);
  EXPECT_EQ(s.faces[1].vertices, (std::vector<uint32_t>{0, 2, 3}));
  EXPECT_NEAR(MaterialOf(s, 0).opacity, .25, 1e-12);
  EXPECT_NEAR(MaterialOf(s, 1).opacity, .75, 1e-12);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(MaterialOf(s, 0).reflectance[c], .25 * Texel(0, c) + .75 * Texel(1, c), 1e-12);
    EXPECT_NEAR(MaterialOf(s, 1).reflectance[c], .75 * Texel(0, c) + .25 * Texel(1, c), 1e-12);
  }
  const std::vector<std::string> lines = Lines(s);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].substr(0, 35), "import: 2 faces partly transparent ");
  EXPECT_EQ(lines[1].substr(0, 40), "import: 2 faces took their reflectance f");
}

// The red reflectance over the quad with coordinates `uv` (the mean of its two triangles,
// of equal area) under a sampler with `wrap_s`, `wrap_t` (0: no sampler).
double RedUnder(const std::vector<float>& uv, int wrap_s, int wrap_t) {
  GltfBuilder b = Quad(uv, BaseColour({1, 1, 1, 1}));
  if (wrap_s != 0 || wrap_t != 0) {
    b.json()["samplers"] = {{{"wrapS", wrap_s == 0 ? 10497 : wrap_s},
                             {"wrapT", wrap_t == 0 ? 10497 : wrap_t}}};
    b.json()["textures"][0]["sampler"] = 0;
  }
  const Scene s = Load(b);
  EXPECT_EQ(s.faces.size(), 2u);
  if (s.faces.size() != 2u) return -1;
  return (MaterialOf(s, 0).reflectance[0] + MaterialOf(s, 1).reflectance[0]) / 2;
}

TEST(GltfTextures, SamplerWrapModesContinueTheImageOutsideTheUnitSquare) {
  constexpr int kRepeat = 10497, kClamp = 33071, kMirror = 33648;
  // u in [1.5, 2], the top row: repeat (with no sampler too) and clamp show the top-right
  // texel, mirrored repeat the top-left one (the second period runs backwards).
  const std::vector<float> right = {1.5f, 0, 2, 0, 2, .5f, 1.5f, .5f};
  EXPECT_NEAR(RedUnder(right, 0, 0), Texel(1, 0), 1e-12);
  EXPECT_NEAR(RedUnder(right, kRepeat, kRepeat), Texel(1, 0), 1e-12);
  EXPECT_NEAR(RedUnder(right, kClamp, kRepeat), Texel(1, 0), 1e-12);
  EXPECT_NEAR(RedUnder(right, kMirror, kRepeat), Texel(0, 0), 1e-12);
  // u in [1, 1.5]: repeat shows the top-left texel, clamp and mirror the top-right.
  const std::vector<float> next = {1, 0, 1.5f, 0, 1.5f, .5f, 1, .5f};
  EXPECT_NEAR(RedUnder(next, kRepeat, kRepeat), Texel(0, 0), 1e-12);
  EXPECT_NEAR(RedUnder(next, kClamp, kRepeat), Texel(1, 0), 1e-12);
  EXPECT_NEAR(RedUnder(next, kMirror, kRepeat), Texel(1, 0), 1e-12);
  // v in [-.5, 0] and [1.5, 2] (glTF's v runs down), the left column: repeat shows the
  // bottom-left texel, clamp (above the top) and mirror the top-left.
  const std::vector<float> above = {0, -.5f, .5f, -.5f, .5f, 0, 0, 0};
  const std::vector<float> below = {0, 1.5f, .5f, 1.5f, .5f, 2, 0, 2};
  EXPECT_NEAR(RedUnder(above, kRepeat, kRepeat), Texel(2, 0), 1e-12);
  EXPECT_NEAR(RedUnder(above, kRepeat, kClamp), Texel(0, 0), 1e-12);
  EXPECT_NEAR(RedUnder(above, kRepeat, kMirror), Texel(0, 0), 1e-12);
  EXPECT_NEAR(RedUnder(below, kRepeat, kRepeat), Texel(2, 0), 1e-12);
  EXPECT_NEAR(RedUnder(below, kRepeat, kMirror), Texel(0, 0), 1e-12);
  // A footprint across the edge, u in [.5, 1.5]: the mean of the top-right texel and what
  // lies beyond it.
  const std::vector<float> across = {.5f, 0, 1.5f, 0, 1.5f, .5f, .5f, .5f};
  EXPECT_NEAR(RedUnder(across, kRepeat, kRepeat), (Texel(1, 0) + Texel(0, 0)) / 2, 1e-12);
  EXPECT_NEAR(RedUnder(across, kClamp, kClamp), Texel(1, 0), 1e-12);
  EXPECT_NEAR(RedUnder(across, kMirror, kRepeat), Texel(1, 0), 1e-12);
}

TEST(GltfTextures, TextureTransformMapsTheCoordinatesFirst) {
  // The whole image, scaled by a half (the top-left texel) and moved right by a half.
  Json material = BaseColour({1, 1, 1, 1});
  material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {.5, 0}}, {"scale", {.5, .5}}}}};
  const Scene s = Load(Quad({0, 0, 1, 0, 1, 1, 0, 1}, material));
  ASSERT_EQ(s.faces.size(), 2u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(MaterialOf(s, 1).reflectance[c], Texel(1, c), 1e-12);
}

TEST(GltfTextures, ImagesInBufferViewsAndFilesReadAsDataUris) {
  const Scene reference = Load(Quad(OverTexel(3), BaseColour({1, 1, 1, 1})));
  ASSERT_EQ(reference.faces.size(), 2u);
  // In the GLB's binary chunk.
  GltfBuilder glb = Quad(OverTexel(3), BaseColour({1, 1, 1, 1}), Json{{"bufferView", 0}});
  glb.json()["images"][0]["bufferView"] = glb.AddView(Png(2, 2, kTexels));
  glb.json()["images"][0]["mimeType"] = "image/png";
  absl::StatusOr<Scene> from_view = LoadGltfData(glb.Glb(), "q.glb", {});
  ASSERT_TRUE(from_view.ok()) << from_view.status();
  EXPECT_EQ(MaterialOf(*from_view, 0).reflectance, MaterialOf(reference, 0).reflectance);
  // A file beside the glTF, named with other letter cases on disk, and in a bundle.
  char pattern[] = "/tmp/radflux_gltf_tex_XXXXXX";
  const std::filesystem::path dir = mkdtemp(pattern);
  std::filesystem::create_directories(dir / "Tex");
  std::ofstream(dir / "Tex" / "Checker.PNG", std::ios::binary) << Png(2, 2, kTexels);
  const GltfBuilder file = Quad(OverTexel(3), BaseColour({1, 1, 1, 1}), {{"uri", "tex/checker.png"}});
  std::ofstream(dir / "q.gltf") << file.Gltf();
  absl::StatusOr<Scene> from_disk = LoadGltfFile((dir / "q.gltf").string(), {});
  ASSERT_TRUE(from_disk.ok()) << from_disk.status();
  EXPECT_EQ(MaterialOf(*from_disk, 0).reflectance, MaterialOf(reference, 0).reflectance);
  const Scene bundled = Load(file, {{"Tex/Checker.PNG", Png(2, 2, kTexels)}});
  EXPECT_EQ(MaterialOf(bundled, 0).reflectance, MaterialOf(reference, 0).reflectance);
  std::filesystem::remove_all(dir);
  // Missing: the factor stays, one line names the file.
  const Scene missing = Load(file);
  ASSERT_EQ(missing.faces.size(), 2u);
  EXPECT_EQ(MaterialOf(missing, 0).reflectance, (Rgb{1, 1, 1}));
  EXPECT_EQ(Lines(missing), std::vector<std::string>{
                                "import: 1 texture not read; the materials using it keep their "
                                "factors (first at tex/checker.png: no such file in the bundle)"});
  // ".." never leaves the bundle.
  const Scene escaping = Load(
      Quad(OverTexel(3), BaseColour({1, 1, 1, 1}), {{"uri", "../checker.png"}}),
      {{"../checker.png", Png(2, 2, kTexels)}});
  EXPECT_EQ(MaterialOf(escaping, 0).reflectance, (Rgb{1, 1, 1}));
}

TEST(GltfTextures, ATextureThatDoesNotExistIsOneErrorLine) {
  Json material = BaseColour({1, 1, 1, 1});
  material["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 7;
  absl::StatusOr<Scene> s = LoadGltfData(Quad(OverTexel(0), material).Gltf(), "q.gltf", {});
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().message(), "q.gltf: material 'material 0': texture 7 does not exist");
}

}  // namespace
}  // namespace radflux
