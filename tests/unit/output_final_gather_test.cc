// The final gather against closed forms: a closed uniform enclosure (every pixel B / pi), the
// same behind a half-opaque plate (half as bright), and a diffuse plate under a small square
// emitter (Lambert's point-to-rectangle form factor).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/subdivide.h"
#include "solver/output/final_gather.h"
#include "solver/output/gather_lights.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "tests/unit/hierarchical_test_scenes.h"
#include "tests/unit/picture_test_scenes.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

using testing::FurnaceCube;
using testing::InsideUnitCube;
using testing::ObjQuad;
using testing::SceneFromObj;

struct Gathered : testing::MeshedScene {
  using MeshedScene::MeshedScene;
  Image RenderDirect(const std::vector<Rgb>& b, const std::vector<Rgb>& indirect,
                     const Camera& camera, int points) const {
    GatherOptions options;
    options.rays = points;
    absl::StatusOr<Image> image =
        RenderDirectPerPixel(mesh, shading, *caster, attributes, b, indirect, camera, options);
    EXPECT_TRUE(image.ok()) << image.status();
    return image.ok() ? *image : Image{};
  }
  Image Render(const std::vector<Rgb>& b, const Camera& camera, int rays, int threads = 0) const {
    GatherOptions options;
    options.rays = rays;
    options.threads = threads;
    absl::StatusOr<Image> image =
        RenderFinalGather(mesh, shading, *caster, attributes, b, camera, options);
    EXPECT_TRUE(image.ok()) << image.status();
    return image.ok() ? *image : Image{};
  }
};

// Unit cube, rho 0.5, E = pi on every face: B = E / (1 - rho) = 2 pi, radiance 2. Given that
// exact B, a gathered path's radiance is (E + rho (E F^ + (B - E))) / pi = 1.5 + 0.5 F^, with F^
// the light sampler's estimate of sum_j F_j = 1 (the gather rays all see R = B - E = pi): the
// light samples are the only noise.
void ExpectUniformRadiance(const Image& image, double pixel_tolerance, double mean_tolerance) {
  ASSERT_EQ(image.rgb.size(), 3u * 32 * 32);
  double sum = 0, worst = 0;
  for (float value : image.rgb) {
    sum += value;
    worst = std::max(worst, std::abs(value / 2.0 - 1));
  }
  EXPECT_NEAR(sum / image.rgb.size(), 2.0, 2.0 * mean_tolerance);
  EXPECT_LT(worst, pixel_tolerance);
}

std::vector<Rgb> FurnaceB(const PatchMesh& mesh) {
  const double b = 2 * std::numbers::pi;
  return std::vector<Rgb>(mesh.size(), Rgb{b, b, b});
}

// Each face one light (6, below the exact chooser's 16), its samples drawn in proportion to the
// cosine within it (F_j >= 0.02 everywhere): F_j / P(j) = sum_k F_k = 1 exactly, so every
// pixel is 2 up to rounding (measured 0 in 5e-5; allowed 1e-3).
TEST(FinalGather, ClosedUniformEnclosureShowsB) {
  const Gathered g(FurnaceCube(), 96);
  ExpectUniformRadiance(g.Render(FurnaceB(g.mesh), InsideUnitCube(), 16), 1e-3, 1e-4);
}

// The cube's faces as 4 x 4 faces each: 96 lights, chosen by the light tree, one light
// sample per visible point. At 512 gather rays a pixel has 64 points: measured, it spreads by
// 3.8% (sigma; 7.5% at 16 points), so the mean of 1024 pixels by 0.12%. Allowed: every pixel
// within 20% (5 sigma), the mean within 0.6%.
TEST(FinalGather, TessellatedEnclosureShowsBWithinNoise) {
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                           {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};
  std::string obj;
  int next = 1;
  for (const auto& f : faces) {
    obj += testing::TessellatedQuad("box", "white", {v[f[0]], v[f[1]], v[f[2]], v[f[3]]}, 4, next);
  }
  const Gathered g(SceneFromObj(obj, "newmtl white\nKd 0.5 0.5 0.5\nKe 1 1 1\n"), 96);
  ASSERT_EQ(MakeGatherLights(g.mesh, g.attributes).mesh.size(), 96u);
  ExpectUniformRadiance(g.Render(FurnaceB(g.mesh), InsideUnitCube(), 512), 0.2, 0.006);
}

// The same image whatever the thread count: seeds are per pixel.
TEST(FinalGather, ImageDoesNotDependOnThreads) {
  const Gathered g(FurnaceCube(), 96);
  const std::vector<Rgb> b(g.mesh.size(), Rgb{1, 2, 3});
  EXPECT_EQ(g.Render(b, InsideUnitCube(), 4, 1).rgb, g.Render(b, InsideUnitCube(), 4, 2).rgb);
}

// The furnace cube with a small black plate 0.01 in front of the camera, filling its view, at
// opacity `opacity` (none at 0): the mean pixel of a 32 x 32 image at 16 paths.
double VeiledFurnaceMean(double opacity) {
  std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "usemtl white\nf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n";
  if (opacity > 0) {
    obj +=
        "v .45 .45 .06\nv .45 .55 .06\nv .55 .55 .06\nv .55 .45 .06\n"
        "usemtl veil\nf 9 10 11 12\n";
  }
  Scene scene =
      SceneFromObj(obj, "newmtl white\nKd 0.5 0.5 0.5\nKe 1 1 1\nnewmtl veil\nKd 0 0 0\n");
  for (Material& m : scene.materials) {
    if (m.name == "veil") m.opacity = opacity;
  }
  const Gathered g(std::move(scene), 96);
  std::vector<Rgb> b = FurnaceB(g.mesh);
  for (uint32_t p = 0; p < g.mesh.size(); ++p) {
    if (g.mesh.patches[p].face == 6) b[p] = Rgb{};
  }
  const Image image = g.Render(b, InsideUnitCube(), 16);
  double sum = 0;
  for (float value : image.rgb) sum += value;
  return sum / static_cast<double>(image.rgb.size());
}

// A camera ray passes the half-opaque black plate with probability 1/2 and then sees the
// furnace's radiance 2: the image is half as bright, within the coin flips' noise (16,384
// paths: sigma 0.4% of the ratio) and the plate's shade on the walls (it subtends < 0.4% of
// their light; 1.2% allowed); an opaque plate shows black.
TEST(FinalGather, AHalfOpaquePlateBeforeTheCameraHalvesTheImage) {
  const double open = VeiledFurnaceMean(0);
  EXPECT_NEAR(open, 2.0, 2e-3);
  EXPECT_NEAR(VeiledFurnaceMean(0.5) / open, 0.5, 0.012);
  EXPECT_EQ(VeiledFurnaceMean(1), 0);
}

// Lambert's form factor from a point to a parallel rectangle [0, a] x [0, b] at height c with a
// corner straight above it.
double CornerFormFactor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * std::numbers::pi);
}

// From the point (px, 0, pz) (normal +y) to the square [-s, s]^2 at height c, by
// superposition of the four corner rectangles (signed: the point may lie outside the
// square's shadow).
double SquareFormFactor(double px, double pz, double s, double c) {
  // G(dx, dz) = sign(dx) sign(dz) corner(|dx|, |dz|); F = G(x1, z1) - G(x0, z1) - G(x1, z0) +
  // G(x0, z0) for the square's edges x0 < x1, z0 < z1 relative to the point.
  auto g = [&](double dx, double dz) {
    return std::copysign(1.0, dx) * std::copysign(1.0, dz) *
           CornerFormFactor(std::abs(dx), std::abs(dz), c);
  };
  const double x0 = -s - px, x1 = s - px, z0 = -s - pz, z1 = s - pz;
  return g(x1, z1) - g(x0, z1) - g(x1, z0) + g(x0, z0);
}

// A 400 x 400 plate (rho 0.5) under a 10 x 10 emitter (rho 0, E = pi) 50 above its centre.
std::string PlateUnderLamp() {
  int next = 1;
  std::string obj = ObjQuad("plate", "white",
                            {{-200, 0, -200}, {-200, 0, 200}, {200, 0, 200}, {200, 0, -200}}, next);
  obj += ObjQuad("lamp", "black", {{-5, 50, -5}, {5, 50, -5}, {5, 50, 5}, {-5, 50, 5}}, next);
  return obj;
}

Camera AbovePlate() {
  Camera camera;
  camera.position = {0, 150, -260};
  camera.look_at = {0, 0, 0};
  camera.width = camera.height = 24;
  camera.vertical_fov_degrees = 50;
  return camera;
}

// Expects each pixel of `image` on the plate to be `scale` rho F(x) (F from the point to the
// lamp) averaged over the pixel's footprint (8 x 8 points), within `pixel_tolerance`, and
// their mean ratio within `mean_tolerance`.
void ExpectPlateFalloff(const Image& image, const Camera& camera, double scale,
                        double pixel_tolerance, double mean_tolerance) {
  const PinholeProjection projection(camera);
  int compared = 0;
  double ratio_sum = 0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      double expected = 0;
      bool on_plate = true;
      for (int k = 0; k < 64; ++k) {
        const Ray ray = projection.RayThrough(x + (k % 8 + 0.5) / 8, y + (k / 8 + 0.5) / 8);
        const double t = -ray.origin.y / ray.direction.y;
        const Vec3 p = ray.origin + ray.direction * t;
        // Off the plate, or through the lamp (its back is black) somewhere in the pixel.
        const double at_lamp = (50 - ray.origin.y) / ray.direction.y;
        const Vec3 l = ray.origin + ray.direction * at_lamp;
        if (!(t > 0) || std::abs(p.x) > 199 || std::abs(p.z) > 199 ||
            (std::abs(l.x) < 6 && std::abs(l.z) < 6)) {
          on_plate = false;
          break;
        }
        expected += scale * 0.5 * SquareFormFactor(p.x, p.z, 5, 50) / 64;
      }
      if (!on_plate) continue;
      ++compared;
      ratio_sum += image.Pixel(x, y)[0] / expected;
      for (int band = 0; band < kBands; ++band) {
        EXPECT_NEAR(image.Pixel(x, y)[band], expected, pixel_tolerance * expected) << x << "," << y;
      }
    }
  }
  EXPECT_GT(compared, 300);
  EXPECT_NEAR(ratio_sum / compared, 1.0, mean_tolerance);
}

// Nothing reflects back to the plate, so its radiance is rho E F(x) / pi = 0.5 F(x) exactly,
// whatever B the plate has. Measured, the pixels (16 paths) lie within 1% of it (the spread of
// the warped solid-angle samples and of the two quadratures), their mean ratio within 0.05%;
// allowed 2% and 0.2%.
TEST(FinalGather, PlateUnderSmallEmitterMatchesClosedForm) {
  const Gathered g(SceneFromObj(PlateUnderLamp()), 200);
  std::vector<Rgb> b(g.mesh.size());
  for (uint32_t p = 0; p < g.mesh.size(); ++p) b[p] = g.attributes.emission[p];
  const Camera camera = AbovePlate();
  ExpectPlateFalloff(g.Render(b, camera, 16), camera, 1.0, 0.02, 0.002);
}

// The direct light per pixel on a plate that is a single patch: its B is one flat value (here
// the plate's mean, as a solve would give), yet the picture follows the falloff under the lamp
// pixel by pixel (a Gouraud picture would show one value: 9x the edge's at the centre). The
// plate's indirect light, regathered, is 0: the lamp reflects nothing (B = E) and the plate
// sees nothing else. Tolerances as the gather's, 16 points a pixel.
TEST(DirectPerPixel, OnePatchPlateFollowsTheFalloffUnderTheLamp) {
  const Gathered g(SceneFromObj(PlateUnderLamp()), 2);
  ASSERT_EQ(g.mesh.size(), 2u);
  std::vector<Rgb> b(g.mesh.size()), indirect(g.mesh.size(), Rgb{});
  for (uint32_t p = 0; p < g.mesh.size(); ++p) {
    const bool lamp = MaxComponent(g.attributes.emission[p]) > 0;
    const double v = lamp ? std::numbers::pi : 0.5 * 0.001;
    b[p] = {v, v, v};
  }
  const Camera camera = AbovePlate();
  ExpectPlateFalloff(g.RenderDirect(b, indirect, camera, 16), camera, 1.0, 0.02, 0.002);
}

// The closed furnace (B = 2 pi, E = pi, rho 0.5 on every face): each point shows
// (E + I + rho H) / pi, H the light samples' sum F_j E_j = pi and I = B - E - rho sum F E =
// pi / 2 (regathered where a pixel centre sees the patch, given to the rest): radiance 2, the
// light samples the only noise (as the gather's furnace: 2% a pixel, 0.5% the mean).
TEST(DirectPerPixel, ClosedFurnaceShowsB) {
  const Gathered cube(FurnaceCube(), 96);
  const double half_pi = std::numbers::pi / 2;
  const std::vector<Rgb> indirect(cube.mesh.size(), Rgb{half_pi, half_pi, half_pi});
  ExpectUniformRadiance(cube.RenderDirect(FurnaceB(cube.mesh), indirect, InsideUnitCube(), 16),
                        0.02, 0.005);
}

// Sizes that disagree and point counts out of range are refused.
TEST(DirectPerPixel, RejectsBadInput) {
  const Gathered g(FurnaceCube(), 6);
  GatherOptions options;
  options.rays = 4;
  const std::vector<Rgb> b(g.mesh.size());
  EXPECT_FALSE(RenderDirectPerPixel(g.mesh, g.shading, *g.caster, g.attributes, b,
                                    std::vector<Rgb>(1), InsideUnitCube(), options)
                   .ok());
  options.rays = 0;
  EXPECT_FALSE(RenderDirectPerPixel(g.mesh, g.shading, *g.caster, g.attributes, b, b,
                                    InsideUnitCube(), options)
                   .ok());
}

// Each face of the cube, 16 patches, is one light of area 1 with the face's emission; an
// L-shaped emitting face (no convex outline) keeps its patches as lights.
TEST(FinalGather, LightsMergeConvexFaces) {
  const Gathered cube(FurnaceCube(), 96);
  const GatherLights lights = MakeGatherLights(cube.mesh, cube.attributes);
  ASSERT_EQ(lights.mesh.size(), 6u);
  for (const Patch& light : lights.mesh.patches) EXPECT_NEAR(light.area, 1.0, 1e-12);
  for (uint32_t p = 0; p < cube.mesh.size(); ++p) {
    const uint32_t light = lights.of_patch[p];
    ASSERT_LT(light, 6u);
    EXPECT_NEAR(Dot(lights.mesh.patches[light].normal, cube.mesh.patches[p].normal), 1, 1e-12);
    EXPECT_EQ(lights.emission[light], cube.attributes.emission[p]);
  }
  int next = 1;
  const std::string l_shape = ObjQuad(
      "l", "lamp", {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, next);
  const Gathered l(
      SceneFromObj(l_shape +
                   ObjQuad("w", "white", {{0, 0, -1}, {1, 0, -1}, {1, 1, -1}, {0, 1, -1}}, next)),
      12);
  const GatherLights l_lights = MakeGatherLights(l.mesh, l.attributes);
  double area = 0;
  uint32_t emitting = 0;
  for (uint32_t p = 0; p < l.mesh.size(); ++p) {
    if (MaxComponent(l.attributes.emission[p]) == 0) {
      EXPECT_EQ(l_lights.of_patch[p], kNoLight);
      continue;
    }
    ++emitting;
    area += l.mesh.patches[p].area;
  }
  EXPECT_GT(l_lights.mesh.size(), 1u);
  double light_area = 0;
  for (const Patch& light : l_lights.mesh.patches) light_area += light.area;
  EXPECT_NEAR(light_area, area, 1e-9);
  EXPECT_NEAR(area, 3.0, 1e-9);
  EXPECT_GT(emitting, 0u);
}

TEST(FinalGather, RejectsBadInput) {
  const Gathered g(FurnaceCube(), 6);
  GatherOptions options;
  options.rays = 0;
  const std::vector<Rgb> b(g.mesh.size());
  EXPECT_FALSE(
      RenderFinalGather(g.mesh, g.shading, *g.caster, g.attributes, b, InsideUnitCube(), options)
          .ok());
  options.rays = 4;
  EXPECT_FALSE(RenderFinalGather(g.mesh, g.shading, *g.caster, g.attributes, std::vector<Rgb>(1),
                                 InsideUnitCube(), options)
                   .ok());
}

}  // namespace
}  // namespace radflux
