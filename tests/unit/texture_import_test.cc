// OBJ textures (solver/scene/face_textures.h, texture_image.h): a face's reflectance is Kd
// times the mean of its map_Kd texture over the face's footprint (sRGB decoded), a face
// whose map_d alpha averages below 1/255 is dropped (any other keeps its mean as its
// opacity), a missing texture is one log line and Kd stays.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "solver/scene/load_scene.h"
#include "solver/scene/texture_image.h"
#include "tests/unit/texture_test_png.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

using testing::GreyPng;
using testing::Linear;
using testing::Png;

// Top-left, top-right, bottom-left, bottom-right: sRGB bytes, the bottom-right transparent.
const std::vector<unsigned char> kTexels = {128, 64, 255, 255, 0,   255, 0,   255,
                                            10,  20, 30,  255, 200, 200, 200, 0};

class TextureImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/radflux_tex_XXXXXX";
    dir_ = mkdtemp(pattern);
    Write("tex/checker.png", Png(2, 2, kTexels));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& path, const std::string& bytes) {
    const fs::path full = fs::path(dir_) / path;
    fs::create_directories(full.parent_path());
    std::ofstream(full, std::ios::binary) << bytes;
    return full.string();
  }
  // A lamp (untextured, facing down at z = 1) and one textured quad in z = 0 with the
  // texture coordinates `uv` (four "vt u v" pairs) and material lines `mtl`.
  absl::StatusOr<Scene> Load(const std::string& uv, const std::string& mtl) {
    Write("s.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\nnewmtl wall\nKd 0.8 0.6 0.4\n" + mtl);
    const std::string obj = Write(
        "s.obj",
        "mtllib s.mtl\nv 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n" +
            uv + "usemtl lamp\nf 1 2 3 4\nusemtl wall\nf 5/1 6/2 7/3 8/4\n");
    return LoadScene(obj, ImportOptions{});
  }
  const Material& Wall(const Scene& s) { return s.materials[s.faces.back().material]; }
  std::string dir_;
};

TEST_F(TextureImportTest, AQuadOverOneTexelTakesExactlyThatTexelsLinearValueTimesKd) {
  // OBJ's v runs up from the bottom row: the top-left texel is u in [0, .5], v in [.5, 1].
  absl::StatusOr<Scene> s =
      Load("vt 0 .5\nvt .5 .5\nvt .5 1\nvt 0 1\n", "map_Kd tex/checker.png\n");
  ASSERT_TRUE(s.ok()) << s.status();
  const Rgb rho = Wall(*s).reflectance;
  EXPECT_NEAR(rho[0], 0.8 * Linear(128), 1e-12);
  EXPECT_NEAR(rho[1], 0.6 * Linear(64), 1e-12);
  EXPECT_NEAR(rho[2], 0.4 * Linear(255), 1e-12);
  EXPECT_EQ(s->materials[s->faces.front().material].reflectance, (Rgb{0.5, 0.5, 0.5}))
      << "the untextured lamp keeps its Kd";
  ASSERT_FALSE(s->import_log.empty());
  EXPECT_EQ(s->import_log.Lines().front(),
            "import: 1 face took its reflectance from textures (map_Kd) (first at " + dir_ +
                "/s.obj:17)");
}

TEST_F(TextureImportTest, AQuadOverTheWholeTextureTakesTheMeanOfItsTexels) {
  absl::StatusOr<Scene> s = Load("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n", "map_Kd TEX/Checker.PNG\n");
  ASSERT_TRUE(s.ok()) << s.status();
  const Rgb rho = Wall(*s).reflectance;
  const double kd[3] = {0.8, 0.6, 0.4};
  for (int b = 0; b < 3; ++b) {
    double mean = 0;
    for (int t = 0; t < 4; ++t) mean += Linear(kTexels[4 * t + b]) / 4;
    EXPECT_NEAR(rho[b], kd[b] * mean, 1e-12) << "band " << b << " (texture found ignoring case)";
  }
  // A quad over half a texel and its mirror image in u: the same mean (repeat, wrap).
  absl::StatusOr<Scene> wrapped =
      Load("vt -.5 .5\nvt -.25 .5\nvt -.25 1\nvt -.5 1\n", "map_Kd tex/checker.png\n");
  ASSERT_TRUE(wrapped.ok());
  EXPECT_NEAR(Wall(*wrapped).reflectance[1], 0.6 * Linear(255), 1e-12)
      << "u in [-.5, -.25] repeats onto [.5, .75]: the top-right texel";
  // Under `-clamp on` the left edge stretches on instead: the top-left texel.
  absl::StatusOr<Scene> clamped =
      Load("vt -.5 .5\nvt -.25 .5\nvt -.25 1\nvt -.5 1\n", "map_Kd -clamp on tex/checker.png\n");
  ASSERT_TRUE(clamped.ok()) << clamped.status();
  EXPECT_NEAR(Wall(*clamped).reflectance[1], 0.6 * Linear(64), 1e-12);
}

TEST_F(TextureImportTest, AMostlyTransparentFaceIsDroppedWithOneLogLine) {
  // The bottom-right texel has alpha 0: a quad over it is cut out, the lamp stays.
  absl::StatusOr<Scene> s = Load("vt .5 0\nvt 1 0\nvt 1 .5\nvt .5 .5\n",
                                 "map_Kd tex/checker.png\nmap_d tex/checker.png\n");
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ(s->faces.size(), 1u);
  const std::vector<std::string> lines = s->import_log.Lines();
  EXPECT_NE(std::find(lines.begin(), lines.end(),
                      "import: 1 face transparent (mean alpha < 1/255) in its alpha "
                      "texture (map_d) dropped (first at " +
                          dir_ + "/s.obj:17)"),
            lines.end());
}

TEST_F(TextureImportTest, AFaceThirtyPercentOpaqueIsKeptWithThatOpacity) {
  // One texel, alpha 77/255 = 0.302 (alpha is linear, not sRGB): the quad over it stays,
  // 0.302 opaque, its reflectance still Kd times the texel's colour.
  Write("tex/veil.png", Png(1, 1, {255, 255, 255, 77}));
  absl::StatusOr<Scene> s =
      Load("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n", "map_Kd tex/veil.png\nmap_d tex/veil.png\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 2u);
  EXPECT_NEAR(Wall(*s).opacity, 77 / 255.0, 1e-7);
  EXPECT_NEAR(Wall(*s).reflectance[0], 0.8, 1e-7);
  EXPECT_EQ(s->materials[s->faces.front().material].opacity, 1) << "the untextured lamp";
  const std::vector<std::string> lines = s->import_log.Lines();
  EXPECT_NE(std::find(lines.begin(), lines.end(),
                      "import: 1 face partly transparent (mean alpha in [1/255, 1)) in its alpha "
                      "texture (map_d) let the transparent fraction through (first at " +
                          dir_ + "/s.obj:17)"),
            lines.end());
}

TEST_F(TextureImportTest, AGreyAlphaMapGivesItsBytesAsOpacityNotTheirDecodedColour) {
  // map_d as a one-channel image (no alpha): its grey is the opacity, as stored. The sRGB
  // curve that colours get would make 128 a 0.216 opacity, not 0.502.
  Write("tex/mask.png", GreyPng(2, 1, {128, 64}));
  absl::StatusOr<Scene> s = Load("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n", "map_d tex/mask.png\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 2u);
  EXPECT_NEAR(Wall(*s).opacity, (128 + 64) / 2 / 255.0, 1e-6);
  EXPECT_NEAR(Wall(*s).reflectance[0], 0.8, 1e-12) << "Kd stays: no map_Kd";
}

TEST_F(TextureImportTest, AMissingTextureKeepsKdAndSaysWhichFile) {
  absl::StatusOr<Scene> s = Load("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n", "map_Kd missing.png\n");
  ASSERT_TRUE(s.ok()) << s.status();
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(Wall(*s).reflectance[b], (Rgb{0.8, 0.6, 0.4})[b], 1e-15);
  ASSERT_FALSE(s->import_log.empty());
  EXPECT_EQ(s->import_log.Lines().front(),
            "import: 1 texture not read; the materials using it keep their Kd/Ke (first at "
            "missing.png: no such file)");
}

TEST_F(TextureImportTest, ABundleReadsItsTexturesAsTheDiskDoes) {
  absl::StatusOr<Scene> disk =
      Load("vt 0 0\nvt 1 0\nvt .5 1\nvt 0 1\n", "map_Kd tex/checker.png\n");
  ASSERT_TRUE(disk.ok());
  SceneBundle bundle{"s.obj", {}};
  for (const char* path : {"s.obj", "s.mtl", "tex/checker.png"}) {
    std::ifstream in(fs::path(dir_) / path, std::ios::binary);
    bundle.files[path] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  absl::StatusOr<Scene> bundled = LoadSceneBundle(bundle, ImportOptions{});
  ASSERT_TRUE(bundled.ok()) << bundled.status();
  EXPECT_EQ(Wall(*bundled).reflectance, Wall(*disk).reflectance);
}

TEST(TextureImage, SrgbDecodeMatchesTheStandardsEndsAndBreak) {
  EXPECT_EQ(SrgbToLinear(0), 0);
  EXPECT_DOUBLE_EQ(SrgbToLinear(1), 1);
  EXPECT_DOUBLE_EQ(SrgbToLinear(0.04045), 0.04045 / 12.92);
  EXPECT_NEAR(SrgbToLinear(0.5), 0.214041, 1e-6);
  for (int v = 0; v < 256; ++v)
    EXPECT_NEAR(LinearToSrgb(SrgbToLinear(v / 255.0)), v / 255.0, 1e-12);
  EXPECT_FALSE(DecodeTexture("not an image", "x.png").ok());
}

TEST(TextureImage, AnImageLargerThanTheLimitIsRefusedBeforeItsPixelsAreAllocated) {
  // A PNG header that claims 5000 x 5000 RGBA texels; no pixel data follows.
  const auto word = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + word(13) + "IHDR" + word(5000) +
                          word(5000) + std::string("\x08\x06\x00\x00\x00", 5) + word(0);
  const absl::StatusOr<TextureImage> image = DecodeTexture(png, "huge.png");
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().message(), "huge.png: 5000 x 5000 texels, more than 16777216");
}

TEST(TextureImage, ClippedFootprintsAgreeWithTheSeparableRectangleMean) {
  absl::StatusOr<TextureImage> image = DecodeTexture(Png(2, 2, kTexels), "checker.png");
  ASSERT_TRUE(image.ok()) << image.status();
  const std::vector<TexCoord> rectangle = {{.1, .2}, {1.7, .2}, {1.7, .9}, {.1, .9}};
  std::vector<TexCoord> pentagon = rectangle;  // the same area with a fifth (collinear) vertex
  pentagon.insert(pentagon.begin() + 1, TexCoord{.9, .2});
  const std::array<double, 4> fast = TextureMean(*image, rectangle, true);
  const std::array<double, 4> clipped = TextureMean(*image, pentagon, true);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(fast[c], clipped[c], 1e-12) << c;
  // Two triangles halving the rectangle average to its mean, weighted by their equal areas.
  const std::array<double, 4> a =
      TextureMean(*image, {rectangle[0], rectangle[1], rectangle[2]}, true);
  const std::array<double, 4> b =
      TextureMean(*image, {rectangle[0], rectangle[2], rectangle[3]}, true);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR((a[c] + b[c]) / 2, fast[c], 1e-12) << c;
}

// The mean of `image`'s texels (repeating, OBJ's v up) at an n x n grid of points in uv's
// bounding box that lie inside uv (even-odd): an independent reading of TextureMean, within
// about the grid's step.
std::array<double, 4> PointSampledMean(const TextureImage& image, const std::vector<TexCoord>& uv,
                                       int n) {
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  for (const TexCoord& c : uv) {
    for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  }
  std::array<double, 4> sum{};
  int inside = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double u = lo[0] + (i + 0.5) / n * (hi[0] - lo[0]);
      const double v = lo[1] + (j + 0.5) / n * (hi[1] - lo[1]);
      bool in = false;
      for (size_t k = 0, m = uv.size() - 1; k < uv.size(); m = k++) {
        if ((uv[k][1] > v) != (uv[m][1] > v) &&
            u < uv[m][0] + (v - uv[m][1]) / (uv[k][1] - uv[m][1]) * (uv[k][0] - uv[m][0])) {
          in = !in;
        }
      }
      if (!in) continue;
      ++inside;
      const auto wrap = [](double t, int size) {
        const int k = static_cast<int>(std::floor(t * size)) % size;
        return k < 0 ? k + size : k;
      };
      const std::array<float, 4>& t = image.texels[static_cast<size_t>(
          wrap(1 - v, image.height) * image.width + wrap(u, image.width))];
      for (int c = 0; c < 4; ++c) sum[c] += t[c];
    }
  }
  for (double& v : sum) v /= inside;
  return sum;
}

TEST(TextureImage, SlantedAndNonConvexFootprintsWeighEachTexelByTheAreaOverIt) {
  // 32 x 32 texels of scattered values; footprints over a few hundred of them, across the
  // image's edge (repeat): a slanted quad (convex: texels wholly inside weigh 1 unclipped),
  // a thin sliver, and an L (not convex: every texel clipped).
  std::vector<unsigned char> rgba(32 * 32 * 4);
  for (size_t k = 0; k < rgba.size(); ++k)
    rgba[k] = static_cast<unsigned char>((k * 97 + 13) % 251);
  absl::StatusOr<TextureImage> image = DecodeTexture(Png(32, 32, rgba), "scattered.png");
  ASSERT_TRUE(image.ok()) << image.status();
  const std::vector<std::vector<TexCoord>> footprints = {
      {{.10, .05}, {.62, .21}, {.55, .83}, {-.07, .58}},
      {{.02, .31}, {.97, .36}, {.96, .40}},
      {{.1, .1}, {.9, .1}, {.9, .3}, {.35, .3}, {.35, .9}, {.1, .9}}};
  for (size_t f = 0; f < footprints.size(); ++f) {
    const std::array<double, 4> exact = TextureMean(*image, footprints[f], true);
    const std::array<double, 4> sampled = PointSampledMean(*image, footprints[f], 2000);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(exact[c], sampled[c], 2e-3) << "footprint " << f;
  }
}

}  // namespace
}  // namespace radflux
