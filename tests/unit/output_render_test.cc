#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/subdivide.h"
#include "solver/output/render.h"
#include "solver/output/shading_mesh.h"
#include "solver/output/vertex_radiosity.h"
#include "solver/raytrace/brute_force_ray_caster.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::AddFace;
using output_testing::TempPath;

struct Cornell {
  Scene scene;
  PatchMesh mesh;
};

Cornell LoadCornell(int64_t patches) {
  Cornell c;
  auto scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return c;
  c.scene = *scene;
  MeshOptions options;
  options.target_patches = patches;
  auto mesh = SubdivideScene(c.scene, options);
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  if (mesh.ok()) c.mesh = *mesh;
  return c;
}

const std::string& ObjectOf(const Cornell& c, uint32_t patch) {
  return c.scene.objects[c.scene.faces[c.mesh.patches[patch].face].object];
}

TEST(OutputRender, CornellRedWallIsOnTheLeft) {
  const Cornell c = LoadCornell(400);
  ASSERT_GT(c.mesh.size(), 0u);
  std::vector<Rgb> b(c.mesh.size(), Rgb{});
  for (uint32_t p = 0; p < c.mesh.size(); ++p) {
    if (ObjectOf(c, p) == "red_wall") b[p] = {1, 1, 1};
  }
  const int n = 64;
  auto caster = EmbreeRayCaster::Create(c.mesh);
  ASSERT_TRUE(caster.ok());
  auto shading = BuildShadingMesh(c.mesh, FaceMaterials(c.scene));
  ASSERT_TRUE(shading.ok());
  auto image = RenderRadiance(c.mesh, **caster, *VertexRadiosity(c.mesh, *shading, b),
                              CornellCamera(n, n), {});
  ASSERT_TRUE(image.ok()) << image.status();
  int lit_left = 0, lit_right = 0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const float value = image->Pixel(x, y)[0];
      // Every red-wall vertex has B = 1, so a lit pixel shows exactly 1/pi.
      if (value == 0) continue;
      EXPECT_NEAR(value, 1 / std::numbers::pi, 1e-6) << x << "," << y;
      ++(x < n / 2 ? lit_left : lit_right);
    }
  }
  EXPECT_EQ(lit_right, 0);
  EXPECT_GT(lit_left, n * n / 20);
  EXPECT_GT(image->Pixel(3, n / 2)[0], 0);      // left edge, mid height: the wall
  EXPECT_EQ(image->Pixel(n - 4, n / 2)[0], 0);  // right edge: the (dark) green wall
}

// B = E + rho * (direct light from the light's centre, with a shadow ray): a rough but
// recognisable Cornell box, for looking at and for colour orientation.
std::vector<Rgb> DirectLightPreview(const Cornell& c, const RayCaster& caster) {
  const PatchAttributes attributes = ComputePatchAttributes(c.scene, c.mesh);
  Vec3 light_centre;
  double light_area = 0;
  Rgb light_e{};
  for (uint32_t p = 0; p < c.mesh.size(); ++p) {
    if (ObjectOf(c, p) != "light") continue;
    light_centre += c.mesh.patches[p].centroid * c.mesh.patches[p].area;
    light_area += c.mesh.patches[p].area;
    light_e = attributes.emission[p];
  }
  light_centre = light_centre / light_area;
  std::vector<Rgb> b = attributes.emission;
  for (uint32_t p = 0; p < c.mesh.size(); ++p) {
    const Patch& patch = c.mesh.patches[p];
    const Vec3 to_light = light_centre - patch.centroid;
    const double r2 = Dot(to_light, to_light);
    const double cos_patch = Dot(patch.normal, to_light) / std::sqrt(r2);
    const double cos_light = to_light.y / std::sqrt(r2);  // the light faces -y
    if (cos_patch <= 0 || cos_light <= 0) continue;
    if (caster.Occluded({patch.centroid, to_light, 1e-4, 1 - 1e-4})) continue;
    const double f = cos_patch * cos_light * light_area / (std::numbers::pi * r2);
    for (int k = 0; k < kBands; ++k) b[p][k] += attributes.reflectance[p][k] * light_e[k] * f;
  }
  return b;
}

TEST(OutputRender, CornellPreviewHasRedLeftGreenRightAndIsThreadIndependent) {
  const Cornell c = LoadCornell(2000);
  auto caster = EmbreeRayCaster::Create(c.mesh);
  ASSERT_TRUE(caster.ok()) << caster.status();
  const std::vector<Rgb> b = DirectLightPreview(c, **caster);
  const std::vector<Rgb> vertex_b =
      *VertexRadiosity(c.mesh, *BuildShadingMesh(c.mesh, FaceMaterials(c.scene)), b);
  const int n = 128;
  RenderOptions options;
  options.samples_per_axis = 2;
  options.threads = 1;
  auto one = RenderRadiance(c.mesh, **caster, vertex_b, CornellCamera(n, n), options);
  options.threads = 2;
  auto two = RenderRadiance(c.mesh, **caster, vertex_b, CornellCamera(n, n), options);
  ASSERT_TRUE(one.ok() && two.ok());
  EXPECT_EQ(one->rgb, two->rgb);
  const float* left = one->Pixel(4, n / 2);
  const float* right = one->Pixel(n - 5, n / 2);
  EXPECT_GT(left[0], 2 * left[1]);             // red wall
  EXPECT_GT(right[1], 2 * right[0]);           // green wall
  const float* light = one->Pixel(n / 2, 18);  // the light panel seen from below
  EXPECT_NEAR(light[0], 17, 1e-3);             // radiance L_e = Ke
  ToneMapOptions tone;
  tone.scale = 1;
  ASSERT_TRUE(WritePng(TempPath("cornell_preview.png"), *one, tone).ok());
}

TEST(OutputRender, BackFacesAndMissesAreBlack) {
  PatchMesh mesh;
  AddFace(mesh, {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {{0, 1, 2, 3}}, {0, 0, 1});
  auto caster = EmbreeRayCaster::Create(mesh);
  ASSERT_TRUE(caster.ok());
  const std::vector<Rgb> vertex_b(4, Rgb{std::numbers::pi, 0, 0});
  Camera camera;
  camera.width = camera.height = 16;
  camera.vertical_fov_degrees = 90;
  camera.position = {0, 0, 5};  // in front: the quad fills the middle of the image
  camera.look_at = {0, 0, 0};
  auto front = RenderRadiance(mesh, **caster, vertex_b, camera, {});
  ASSERT_TRUE(front.ok());
  EXPECT_FLOAT_EQ(front->Pixel(8, 8)[0], 1.0f);  // B/pi
  EXPECT_EQ(front->Pixel(0, 0)[0], 0.0f);        // corner ray misses
  camera.position = {0, 0, -5};                  // behind
  auto back = RenderRadiance(mesh, **caster, vertex_b, camera, {});
  ASSERT_TRUE(back.ok());
  for (float value : back->rgb) ASSERT_EQ(value, 0.0f);
}

// Maps plane coordinates (s, t) to 3D in a tilted plane.
struct TiltedPlane {
  Vec3 origin, a, b;
  Vec3 At(double s, double t) const { return origin + a * s + b * t; }
  Vec3 Normal() const { return Normalize(Cross(a, b)); }
};

TEST(OutputRender, InterpolationOfLinearFunctionIsExactAtHitsAgainstBruteForce) {
  const Frame frame = Frame::FromNormal(Normalize(Vec3{0.3, -0.5, 0.8}));
  const TiltedPlane plane{{1, 2, 3}, frame.s, frame.t};
  const TiltedPlane other{{-20, 0, 0}, Vec3{0, 0, 1}, Normalize(Vec3{1, 1, 0})};
  PatchMesh mesh;  // a general convex quad (not a parallelogram), a triangle, a parallelogram
  AddFace(mesh, {plane.At(0, 0), plane.At(4, 0), plane.At(3, 2), plane.At(0.5, 3)}, {{0, 1, 2, 3}},
          plane.Normal());
  AddFace(mesh, {other.At(0, 0), other.At(3, 0.5), other.At(1, 2.5)}, {{0, 1, 2, 2}},
          other.Normal());
  AddFace(mesh, {plane.At(6, 0), plane.At(9, 0), plane.At(10, 2), plane.At(7, 2)}, {{0, 1, 2, 3}},
          plane.Normal());
  const Vec3 slope[3] = {{1, 2, 3}, {-0.5, 0.25, 4}, {0, 0, -2}};
  auto f = [&](const Vec3& p) {
    return Rgb{Dot(slope[0], p) + 1, Dot(slope[1], p), Dot(slope[2], p) - 3};
  };
  std::vector<Rgb> vertex_values;
  for (const Vec3& p : mesh.positions) vertex_values.push_back(f(p));
  auto embree = EmbreeRayCaster::Create(mesh);
  ASSERT_TRUE(embree.ok());
  const BruteForceRayCaster brute(mesh);
  int hits = 0, second_triangle_hits = 0;
  double max_bilinear_error = 0;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    for (int i = 1; i < 12; ++i) {
      for (int j = 1; j < 12; ++j) {
        // Bilinear parameters of the target, kept off the v0-v2 diagonal (where the
        // brute-force caster, which splits quads there, can miss between its triangles).
        const double s = (i + 0.25) / 12.5, t = (j - 0.125) / 12.5;
        const Vec3 target = mesh.Vertex(p, 0) * ((1 - s) * (1 - t)) +
                            mesh.Vertex(p, 1) * (s * (1 - t)) + mesh.Vertex(p, 2) * (s * t) +
                            mesh.Vertex(p, 3) * ((1 - s) * t);
        const Vec3 origin = target + patch.normal * 7 + Vec3{0.7, -0.4, 0.2};
        const Ray ray{origin, target - origin, 0, 10};
        const Hit hit = (*embree)->Intersect(ray);
        const Hit exact = brute.Intersect(ray);
        ASSERT_EQ(hit.patch, p);
        ASSERT_EQ(exact.patch, p) << i << " " << j;
        if (patch.IsTriangle()) {
          EXPECT_LE(hit.u + hit.v, 1 + 1e-5);
        }
        if (hit.u + hit.v > 1) ++second_triangle_hits;
        const Rgb expected = f(ray.origin + ray.direction * exact.t);
        const Rgb got = InterpolateAtHit(mesh, vertex_values, hit);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(got[k], expected[k], 2e-4) << p << " " << i << " " << j;
        // Bilinear weights (1-u)(1-v), u(1-v), uv, (1-u)v on Embree's u,v would be exact
        // only on a parallelogram: Embree's quad u,v are per-triangle, not the quad's own
        // bilinear parameters, which PatchVertexWeights recovers from the hit point.
        const double u = hit.u, v = hit.v;
        const std::array<double, 4> bilinear = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
        double at_bilinear = 0;
        for (int k = 0; k < 4; ++k) at_bilinear += bilinear[k] * vertex_values[patch.v[k]][0];
        if (!patch.IsTriangle()) {
          max_bilinear_error = std::max(max_bilinear_error, std::abs(at_bilinear - expected[0]));
        }
        ++hits;
      }
    }
  }
  EXPECT_EQ(hits, 3 * 11 * 11);
  EXPECT_GT(second_triangle_hits, 20);  // both halves of the quad were exercised
  EXPECT_GT(max_bilinear_error, 0.1);   // why PatchVertexWeights inverts the bilinear map
}

TEST(OutputRender, QuadWeightsAreBilinearInTheQuadsOwnParameters) {
  PatchMesh mesh;  // a trapezoid: bilinear parameters differ from Embree's per-triangle u,v
  AddFace(mesh, {{0, 0, 0}, {4, 0, 0}, {3, 2, 0}, {1, 2, 0}}, {{0, 1, 2, 3}}, {0, 0, 1});
  AddFace(mesh, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2, 2}}, {0, 0, 1});
  using W = std::array<double, 4>;
  // The first triangle's u,v (0.375, 0.5) is the point (2, 1), the trapezoid's bilinear
  // centre s = t = 0.5 (per-triangle weights there would be 0.125, 0.375, 0, 0.5).
  const W w = PatchVertexWeights(mesh, 0, 0.375, 0.5);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(w[k], 0.25, 1e-12) << k;
  const W corner = PatchVertexWeights(mesh, 0, 1, 1);  // the second triangle's v0 = v2
  EXPECT_NEAR(corner[2], 1, 1e-12);
  // Along the edge v1-v2 (u + v = 1 in the first triangle is the diagonal, not an edge),
  // the weights are linear in the distance: halfway gives 1/2, 1/2.
  const W edge = PatchVertexWeights(mesh, 0, 1, 0.5);  // second triangle: u' = 0, v' = 0.5
  EXPECT_NEAR(edge[1], 0.5, 1e-12);
  EXPECT_NEAR(edge[2], 0.5, 1e-12);
  EXPECT_EQ(PatchVertexWeights(mesh, 1, 0.25, 0.5), (W{0.25, 0.25, 0.5, 0}));
}

// A linear field on a flat wall of three faces with T-junctions: the picture shows it
// exactly, so there is no jump where the faces meet (x = 2).
TEST(OutputRender, FlatWallOfSeveralFacesShowsALinearFieldWithoutAJump) {
  PatchMesh mesh;
  output_testing::AddTJunctionWall(mesh);
  auto field = [](const Vec3& p) { return 2 + 0.5 * p.x - 0.75 * p.y; };
  std::vector<Rgb> b;
  for (const Patch& patch : mesh.patches) {
    const double value = field(patch.centroid);
    b.push_back({value, value, value});
  }
  auto caster = EmbreeRayCaster::Create(mesh);
  ASSERT_TRUE(caster.ok());
  const std::vector<Rgb> vertex_b =
      *VertexRadiosity(mesh, output_testing::ShadeOneMaterial(mesh), b);
  Camera camera;
  camera.position = {2, 0.5, 1};  // sees x in [1.53, 2.47], y in [0.03, 0.97]
  camera.look_at = {2, 0.5, 0};
  camera.vertical_fov_degrees = 50;
  camera.width = camera.height = 96;
  auto image = RenderRadiance(mesh, **caster, vertex_b, camera, {});
  ASSERT_TRUE(image.ok());
  const PinholeProjection projection(camera);
  int left = 0, right = 0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = projection.RayThrough(x + 0.5, y + 0.5);
      const Vec3 p = ray.origin + ray.direction * (-ray.origin.z / ray.direction.z);
      ++(p.x < 2 ? left : right);
      EXPECT_NEAR(image->Pixel(x, y)[0], field(p) / std::numbers::pi, 2e-6) << x << "," << y;
    }
  }
  EXPECT_GT(left, 1000);  // the picture spans the edge x = 2
  EXPECT_GT(right, 1000);
}

TEST(OutputRender, InvalidInputsAreErrors) {
  PatchMesh mesh;
  AddFace(mesh, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 1, 2, 2}}, {0, 0, 1});
  auto caster = EmbreeRayCaster::Create(mesh);
  ASSERT_TRUE(caster.ok());
  Camera camera = CornellCamera(0, 10);
  EXPECT_FALSE(RenderRadiance(mesh, **caster, std::vector<Rgb>(3), camera, {}).ok());
  camera = CornellCamera(4, 4);
  camera.up = {0, 0, 1};  // parallel to the view direction
  EXPECT_FALSE(RenderRadiance(mesh, **caster, std::vector<Rgb>(3), camera, {}).ok());
  EXPECT_FALSE(RenderRadiance(mesh, **caster, std::vector<Rgb>(2), CornellCamera(4, 4), {}).ok());
}

}  // namespace
}  // namespace radflux
