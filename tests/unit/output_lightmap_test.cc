// Lightmaps: the atlas's charts never overlap and keep their gutter; the baked texels of a
// flat wall are its B / pi; the GLB round-trips through tinygltf with both UV sets and the
// image, whose decoded texels give back B within the 8-bit quantisation.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "solver/mesh/subdivide.h"
#include "solver/output/lightmap_atlas.h"
#include "solver/output/lightmap_bake.h"
#include "solver/output/lightmap_gltf.h"
#include "solver/output/tone_map.h"
#include "solver/output/vertex_radiosity.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"
#include "tests/unit/output_test_meshes.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

using output_testing::TempPath;

struct Meshed {
  Scene scene;
  PatchMesh mesh;
  ShadingMesh shading;
  Meshed(Scene s, int64_t patches) : scene(std::move(s)) {
    MeshOptions options;
    options.target_patches = patches;
    mesh = *SubdivideScene(scene, options);
    shading = *BuildShadingMesh(mesh, FaceMaterials(scene));
  }
};

TEST(Lightmap, CornellChartsNeverOverlapAndKeepTheGutter) {
  auto scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok()) << scene.status();
  const Meshed m(*scene, 2000);
  for (int size : {64, 512}) {
    absl::StatusOr<LightmapAtlas> atlas = BuildLightmapAtlas(m.mesh, size);
    ASSERT_TRUE(atlas.ok()) << atlas.status();
    const auto& charts = atlas->charts;
    double used = 0;
    for (size_t a = 0; a < charts.size(); ++a) {
      EXPECT_GE(charts[a].x, 0);
      EXPECT_GE(charts[a].y, 0);
      EXPECT_LE(charts[a].x + charts[a].width, size);
      EXPECT_LE(charts[a].y + charts[a].height, size);
      used += double(charts[a].width) * charts[a].height;
      for (size_t b = a + 1; b < charts.size(); ++b) {
        const bool apart = charts[a].x + charts[a].width <= charts[b].x ||
                           charts[b].x + charts[b].width <= charts[a].x ||
                           charts[a].y + charts[a].height <= charts[b].y ||
                           charts[b].y + charts[b].height <= charts[a].y;
        EXPECT_TRUE(apart) << "charts " << a << " and " << b << " overlap at size " << size;
      }
    }
    EXPECT_GT(used, 0.3 * size * size);  // the shelves use the square reasonably
    // Every vertex of a face lies inside its chart's rectangle less the gutter.
    for (const Patch& patch : m.mesh.patches) {
      const LightmapChart& chart = charts[atlas->chart_of_face[patch.face]];
      for (int k = 0; k < patch.VertexCount(); ++k) {
        const Point2 t = atlas->Texel(chart, m.mesh.positions[patch.v[k]]);
        EXPECT_GE(t.x, chart.x + atlas->gutter - 1e-9);
        EXPECT_GE(t.y, chart.y + atlas->gutter - 1e-9);
        EXPECT_LE(t.x, chart.x + chart.width - atlas->gutter + 1e-9);
        EXPECT_LE(t.y, chart.y + chart.height - atlas->gutter + 1e-9);
      }
    }
  }
  EXPECT_FALSE(BuildLightmapAtlas(m.mesh, 8).ok());
  EXPECT_FALSE(BuildLightmapAtlas(m.mesh, 64, 1).ok());
}

// A 400 x 300 wall (z = 0, facing +z) with B linear in x and y, per band: the vertex fits
// reproduce a linear field, so every texel centre on the wall is B / pi there (float).
Rgb WallB(const Vec3& p) {
  const double f = 1 + p.x / 400 + 2 * p.y / 300;
  return {10 * f, 20 * f, 5 * f};
}

struct Wall {
  Meshed m;
  std::vector<Rgb> b;
  Wall()
      : m(testing::SceneFromObj(
              "v 0 0 0\nv 400 0 0\nv 400 300 0\nv 0 300 0\nusemtl white\nf 1 2 3 4\n"),
          48) {
    for (const Patch& patch : m.mesh.patches) b.push_back(WallB(patch.centroid));
  }
  // The point of the wall at the centre of texel (x, y) of the atlas's only chart.
  static Vec3 At(const LightmapAtlas& atlas, int x, int y) {
    const LightmapChart& c = atlas.charts[0];
    const double s = c.s0 + (x + 0.5 - c.x - atlas.gutter) / atlas.texels_per_unit;
    const double t = c.t0 + (y + 0.5 - c.y - atlas.gutter) / atlas.texels_per_unit;
    return c.frame.s * s + c.frame.t * t;  // the wall's plane passes through the origin
  }
  // Calls visit(x, y, B there) for every texel of the chart whose centre is on the wall;
  // returns how many.
  template <typename Visit>
  static int ForEachTexelOnWall(const LightmapAtlas& atlas, Visit&& visit) {
    const LightmapChart& c = atlas.charts[0];
    int count = 0;
    for (int y = c.y; y < c.y + c.height; ++y) {
      for (int x = c.x; x < c.x + c.width; ++x) {
        const Vec3 p = At(atlas, x, y);
        if (p.x < 0 || p.y < 0 || p.x > 400 || p.y > 300) continue;
        ++count;
        visit(x, y, WallB(p));
      }
    }
    return count;
  }
};

TEST(Lightmap, FlatWallTexelsAreBOverPi) {
  const Wall wall;
  const LightmapAtlas atlas = *BuildLightmapAtlas(wall.m.mesh, 64);
  ASSERT_EQ(atlas.charts.size(), 1u);
  const Image image =
      BakeLightmap(wall.m.mesh, atlas, *VertexRadiosity(wall.m.mesh, wall.m.shading, wall.b));
  const LightmapChart& c = atlas.charts[0];
  const int checked = Wall::ForEachTexelOnWall(atlas, [&](int x, int y, const Rgb& b) {
    for (int band = 0; band < kBands; ++band) {
      EXPECT_NEAR(image.Pixel(x, y)[band], b[band] / std::numbers::pi, 1e-5 * b[band])
          << x << "," << y;
    }
  });
  EXPECT_GT(checked, 1000);
  // The gutter repeats the edge: the texel left of the chart's first column is its neighbour's.
  const int y = c.y + c.height / 2, x = c.x + atlas.gutter - 1;
  EXPECT_GT(image.Pixel(x, y)[0], 0.9 * image.Pixel(x + 1, y)[0]);
}

double SrgbDecode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

TEST(Lightmap, GlbRoundTripsThroughTinyGltf) {
  const Wall wall;
  GltfOptions options;
  options.metres_per_unit = 0.001;
  options.tone.scale = 0.1;
  const std::string path = TempPath("lightmap.glb");
  ASSERT_TRUE(WriteLightmapGlb(path, wall.m.mesh, wall.m.shading, wall.b, 64, options).ok());
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path)) << error;
  const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
  for (const char* a : {"POSITION", "NORMAL", "TEXCOORD_0", "TEXCOORD_1"}) {
    EXPECT_TRUE(primitive.attributes.count(a)) << a;
  }
  const tinygltf::Material& material = model.materials.at(0);
  EXPECT_EQ(material.emissiveTexture.index, 0);
  EXPECT_EQ(material.emissiveTexture.texCoord, 1);
  ASSERT_TRUE(material.extensions.count("KHR_materials_emissive_strength"));
  const double strength = material.extensions.at("KHR_materials_emissive_strength")
                              .Get("emissiveStrength")
                              .GetNumberAsDouble();
  const double scale = material.extras.Get("radflux_radiance_scale").GetNumberAsDouble();
  EXPECT_DOUBLE_EQ(scale, 0.1);
  // The largest radiance is 40 / pi; times 0.1 it is above 1, so it sets the strength.
  EXPECT_NEAR(strength, 0.1 * 20 * 4 / std::numbers::pi, 0.02 * strength);
  const tinygltf::Image& image = model.images.at(0);
  ASSERT_EQ(image.width, 64);
  ASSERT_EQ(image.height, 64);
  ASSERT_GE(image.component, 3);
  const LightmapAtlas atlas = *BuildLightmapAtlas(wall.m.mesh, 64);
  const LightmapChart& c = atlas.charts[0];
  const int checked = Wall::ForEachTexelOnWall(atlas, [&](int x, int y, const Rgb& b) {
    for (int band = 0; band < kBands; ++band) {
      const int byte = image.image[(static_cast<size_t>(y) * 64 + x) * image.component + band];
      const double decoded = std::numbers::pi * strength / scale * SrgbDecode(byte / 255.0);
      // Half the larger of the 8-bit sRGB code's steps either side of this byte, in B.
      const double below = SrgbDecode(byte / 255.0) - SrgbDecode(std::max(0, byte - 1) / 255.0);
      const double above = SrgbDecode(std::min(255, byte + 1) / 255.0) - SrgbDecode(byte / 255.0);
      const double step = std::numbers::pi * strength / scale * std::max(below, above) / 2;
      EXPECT_NEAR(decoded, b[band], step * 1.001 + 1e-9) << x << "," << y << " band " << band;
    }
  });
  EXPECT_GT(checked, 1000);
  // TEXCOORD_1 in the file is the atlas's UV of each vertex.
  const tinygltf::Accessor& uv = model.accessors.at(primitive.attributes.at("TEXCOORD_1"));
  const tinygltf::BufferView& view = model.bufferViews.at(uv.bufferView);
  std::vector<float> uvs(2 * uv.count);
  std::memcpy(uvs.data(), model.buffers[0].data.data() + view.byteOffset + uv.byteOffset,
              uvs.size() * 4);
  for (size_t v = 0; v < wall.m.mesh.positions.size(); ++v) {
    const Point2 expected = atlas.Uv(c, wall.m.mesh.positions[v]);
    EXPECT_NEAR(uvs[2 * v], expected.x, 1e-6);
    EXPECT_NEAR(uvs[2 * v + 1], expected.y, 1e-6);
  }
}

}  // namespace
}  // namespace radflux
