// The picture's regathered indirect light against closed forms: a closed furnace (every ray
// meets R = B - E, so I = rho R exactly), and a plate under a reflecting square (I = rho R F,
// F the parallel squares' C-11); patches no pixel centre sees keep the solve's I.
#include "solver/output/indirect_regather.h"

#include <gtest/gtest.h>

#include <numbers>
#include <numeric>
#include <vector>

#include "tests/unit/hierarchical_test_scenes.h"
#include "tests/unit/howell_closed_forms.h"
#include "tests/unit/picture_test_scenes.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

using testing::InsideUnitCube;

// A meshed scene's regathered indirect light, seeded with 1.
struct Regathered : testing::MeshedScene {
  using MeshedScene::MeshedScene;
  std::vector<Rgb> Indirect(const std::vector<Rgb>& b, const std::vector<Rgb>& solved,
                            const Camera& camera, int threads = 0) const {
    const VertexFit fit = *VertexFit::Build(mesh, shading);
    absl::StatusOr<std::vector<Rgb>> i = RegatherShownIndirect(mesh, fit, *caster, attributes, b,
                                                               solved, camera, /*seed=*/1, threads);
    EXPECT_TRUE(i.ok()) << i.status();
    return i.ok() ? *i : std::vector<Rgb>(mesh.size());
  }
};

// Every pixel centre of a camera inside a closed cube meets one patch's front: the counts
// add up to the pixels.
TEST(PixelsPerPatch, CountsEveryPixelCentreOnce) {
  const Regathered cube(testing::FurnaceCube(), 96);
  const Camera camera = InsideUnitCube();
  const std::vector<uint32_t> pixels = PixelsPerPatch(cube.mesh, *cube.caster, camera, 0);
  ASSERT_EQ(pixels.size(), cube.mesh.size());
  EXPECT_EQ(std::accumulate(pixels.begin(), pixels.end(), uint64_t{0}), 32u * 32u);
}

// The furnace (E = pi, rho 0.5, B = 2 pi on every face): every ray meets R = B - E = pi, an
// emitter's reflection counted, so a shown patch's I is rho pi = pi / 2 to rounding; a patch
// no pixel centre sees (the faces behind the camera) keeps the value it was given. The same
// values on one thread as on all.
TEST(RegatherShownIndirect, ClosedFurnaceGathersRhoTimesR) {
  const Regathered cube(testing::FurnaceCube(), 96);
  const double b = 2 * std::numbers::pi;
  const std::vector<Rgb> radiosity(cube.mesh.size(), Rgb{b, b, b});
  const std::vector<Rgb> sentinel(cube.mesh.size(), Rgb{7, 7, 7});
  const Camera camera = InsideUnitCube();
  const std::vector<Rgb> i = cube.Indirect(radiosity, sentinel, camera);
  const std::vector<uint32_t> pixels = PixelsPerPatch(cube.mesh, *cube.caster, camera, 0);
  int shown = 0;
  for (uint32_t p = 0; p < cube.mesh.size(); ++p) {
    for (int band = 0; band < kBands; ++band) {
      EXPECT_NEAR(i[p][band], pixels[p] > 0 ? std::numbers::pi / 2 : 7.0, 1e-9) << p;
    }
    shown += pixels[p] > 0;
  }
  EXPECT_GT(shown, 16);
  EXPECT_LT(shown, static_cast<int>(cube.mesh.size()));
  const std::vector<Rgb> one_thread = cube.Indirect(radiosity, sentinel, camera, 1);
  for (uint32_t p = 0; p < cube.mesh.size(); ++p) EXPECT_EQ(i[p], one_thread[p]) << p;
}

// A unit square at y = 0 facing up under a reflecting unit square at y = 0.5 facing down, no
// emitters: with the upper square's B = R (uniform), a lower patch's I is rho R times its form
// factor to the square, so their area-weighted mean is rho R F, F = C-11(1, 1, 0.5) = 0.4152.
// The camera between them sees the whole lower square. Measured: 0.3% off (~25,000 stratified
// rays in all, 8 per pixel that sees a patch); allowed 1%.
TEST(RegatherShownIndirect, PlateUnderAReflectorMatchesTheParallelSquares) {
  int next = 1;
  std::string obj =
      testing::ObjQuad("floor", "white", {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, next);
  obj += testing::ObjQuad("reflector", "white",
                          {{0, 0.5, 0}, {1, 0.5, 0}, {1, 0.5, 1}, {0, 0.5, 1}}, next);
  const Regathered g(testing::SceneFromObj(obj), 64);
  const double r = 3;
  std::vector<Rgb> radiosity(g.mesh.size(), Rgb{});
  for (uint32_t p = 0; p < g.mesh.size(); ++p) {
    if (g.mesh.patches[p].centroid.y > 0.25) radiosity[p] = Rgb{r, r, r};
  }
  Camera camera;
  camera.position = {0.5, 0.25, 0.5};
  camera.look_at = {0.5, 0, 0.5};
  camera.up = {0, 0, 1};
  camera.vertical_fov_degrees = 150;
  camera.width = camera.height = 64;
  const std::vector<Rgb> i = g.Indirect(radiosity, std::vector<Rgb>(g.mesh.size()), camera);
  const std::vector<uint32_t> pixels = PixelsPerPatch(g.mesh, *g.caster, camera, 0);
  double area = 0, weighted = 0;
  for (uint32_t p = 0; p < g.mesh.size(); ++p) {
    if (g.mesh.patches[p].centroid.y > 0.25) continue;
    EXPECT_GT(pixels[p], 0u) << p;
    area += g.mesh.patches[p].area;
    weighted += g.mesh.patches[p].area * i[p][0];
  }
  const double expected = 0.5 * r * testing::ParallelRectangles(1, 1, 0.5);
  EXPECT_NEAR(area, 1.0, 1e-12);
  EXPECT_NEAR(weighted / area, expected, 0.01 * expected);
}

// Sizes that disagree are refused.
TEST(RegatherShownIndirect, RejectsBadSizes) {
  const Regathered cube(testing::FurnaceCube(), 6);
  const std::vector<Rgb> b(cube.mesh.size());
  const VertexFit fit = *VertexFit::Build(cube.mesh, cube.shading);
  EXPECT_FALSE(RegatherShownIndirect(cube.mesh, fit, *cube.caster, cube.attributes, b,
                                     std::vector<Rgb>(1), InsideUnitCube(), 1, 0)
                   .ok());
  EXPECT_FALSE(RegatherShownIndirect(cube.mesh, fit, *cube.caster, cube.attributes,
                                     std::vector<Rgb>(1), b, InsideUnitCube(), 1, 0)
                   .ok());
}

}  // namespace
}  // namespace radflux
