// Bright reflectors (bright_reflectors.h): which unknowns are marked, and that monte_carlo's
// rows estimate their columns without bias (the seeds' mean against the exact form factor)
// and with far less spread than the cosine rays alone (a receiver's heavy-tailed error on
// office2's light switch: +152% on one seed).
#include "solver/formfactor/bright_reflectors.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/formfactor/polygon_form_factor.h"
#include "test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::RowFixture;
using testing::SceneFromObj;

// A lamp (Ke 1, rho 0.5) standing at the edge of a 20 cm square reflector lying on z = 0, a
// sliver of reflector (1 mm square) as close to the lamp, a 10 cm receiver 1 m away facing
// both (it sees the reflector's whole top, unoccluded, and the lamp), and a 6 m floor 1 m
// below, which makes the scene's emitted power per unit area small.
constexpr std::array<Vec3, 4> kReflector{Vec3{-.29, -.1, 0}, Vec3{-.09, -.1, 0}, Vec3{-.09, .1, 0},
                                         Vec3{-.29, .1, 0}};
std::string LampBesideReflector() {
  int next = 1;
  std::string obj =
      ObjQuad("lamp", "lamp", {{-.3, -.1, 0}, {-.3, .1, 0}, {-.3, .1, .1}, {-.3, -.1, .1}}, next);
  obj += ObjQuad("reflector", "white", {kReflector.begin(), kReflector.end()}, next);
  obj += ObjQuad("sliver", "white",
                 {{-.29, .15, 0}, {-.289, .15, 0}, {-.289, .151, 0}, {-.29, .151, 0}}, next);
  obj += ObjQuad("receiver", "white", {{1, .05, .2}, {1, -.05, .2}, {1, -.05, .3}, {1, .05, .3}},
                 next);
  obj += ObjQuad("floor", "white", {{-3, -3, -1}, {3, -3, -1}, {3, 3, -1}, {-3, 3, -1}}, next);
  return obj;
}

uint32_t PatchOf(const RowFixture& f, const std::string& object) {
  uint32_t p = 0;
  while (f.ObjectOf(p) != object) ++p;
  return p;
}

// The receiver's exact form factor to the reflector: Lambert's point-to-polygon form factor
// averaged over a 40 x 40 midpoint grid of the receiver (nothing occludes it).
double ExactReceiverToReflector(const RowFixture& f) {
  const Vec3 n = f.mesh.patches[PatchOf(f, "receiver")].normal;
  const int m = 40;
  double sum = 0;
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      const Vec3 x{1, -.05 + .1 * (a + .5) / m, .2 + .1 * (b + .5) / m};
      sum += PointToPolygonFormFactor(x, n, kReflector);
    }
  }
  return sum / (m * m);
}

TEST(BrightReflectors, MarksTheReflectorBesideTheLampOnly) {
  RowFixture f(SceneFromObj(LampBesideReflector()), MeshOptions{});
  const RowContext lit = WithBrightReflectors(f.context);
  EXPECT_EQ(lit.emitter[PatchOf(f, "reflector")], 1);  // lit far above the scene's mean
  EXPECT_GT(lit.emission[PatchOf(f, "reflector")], 0);
  EXPECT_EQ(lit.emitter[PatchOf(f, "sliver")], 0);    // as bright, but next to no power
  EXPECT_EQ(lit.emitter[PatchOf(f, "receiver")], 0);  // 1 m away
  EXPECT_EQ(lit.emitter[PatchOf(f, "floor")], 0);
  EXPECT_EQ(lit.emitter[PatchOf(f, "lamp")], 1);  // the emitter stays one
  // The scene's own emission is unchanged: only the rows' columns are sampled differently.
  EXPECT_EQ(f.context.emitter[PatchOf(f, "reflector")], 0);
}

// Over 200 seeds at k = 64, the receiver's entry towards the reflector has the exact form
// factor as its mean (within 4 standard errors) and spreads by under half the cosine rays'
// multinomial spread sqrt(F (1 - F) / k), F = 0.0017 (measured: 0.36 of it; the rays alone,
// which meet the reflector once in ~600: 2.5 times it, the mean 1.6 times the exact).
TEST(BrightReflectors, ReceiverRowSamplesTheReflectorUnbiasedAndTight) {
  RowFixture f(SceneFromObj(LampBesideReflector()), MeshOptions{});
  const uint32_t receiver = PatchOf(f, "receiver"), reflector = PatchOf(f, "reflector");
  const double exact = ExactReceiverToReflector(f);
  FormFactorOptions o;
  o.rays = 64;
  o.cutoff = 0;
  const int seeds = 200;
  const testing::SeedMean m = testing::MeanOverSeeds(seeds, [&](uint64_t seed) {
    o.seed = seed;
    const CsrMatrix rows = f.Rows(o);
    const auto cols = rows.RowCols(receiver);
    const auto vals = rows.RowValues(receiver);
    double v = 0;
    for (size_t k = 0; k < cols.size(); ++k) v += cols[k] == reflector ? vals[k] : 0;
    return v;
  });
  const double sd = m.standard_error * std::sqrt(seeds);
  const double multinomial = std::sqrt(exact * (1 - exact) / o.rays);
  std::printf("  F = %.5f +- %.5f (exact %.5f), spread %.5f, the rays' %.5f\n", m.mean,
              m.standard_error, exact, sd, multinomial);
  EXPECT_NEAR(m.mean, exact, 4 * m.standard_error + 1e-12);
  EXPECT_LT(sd, 0.5 * multinomial);
}

// A closed unit box of one-patch walls with a 10 cm lamp 2 cm over the floor, facing it:
// the floor is a bright reflector, and every ray of the lamp's row meets a wall, so the row
// sums to exactly 1 on every seed when its cosine rays keep the floor's column. Split into
// a light-sampled floor column and the rays' other walls, the two parts' noise would not
// cancel (sd about sqrt(p (1 - p) / k), p the other walls' share; office2's lamp: its row
// sum spread 0.88..1.04 over seeds, 0.94..1.0 before, and the energy balance failed).
TEST(BrightReflectors, EmittersRowStaysOneDrawOfItsRays) {
  int next = 1;
  std::string obj =
      testing::InwardUnitCubeObj({"white", "white", "white", "white", "white", "white"}, next);
  obj += ObjQuad("lamp", "lamp",
                 {{.45, .45, .02}, {.45, .55, .02}, {.55, .55, .02}, {.55, .45, .02}}, next);
  MeshOptions one_patch_a_face;
  one_patch_a_face.follow_contacts = false;  // the floor stays one patch under the lamp
  RowFixture f(SceneFromObj(obj), one_patch_a_face);
  ASSERT_EQ(f.mesh.size(), 7u);
  const uint32_t floor = 0;  // the cube's face z = 0, its first
  ASSERT_EQ(f.mesh.patches[floor].normal.z, 1);
  ASSERT_EQ(WithBrightReflectors(f.context).emitter[floor], 1);
  const uint32_t lamp = PatchOf(f, "lamp");
  FormFactorOptions o;
  o.rays = 64;
  o.cutoff = 0;
  for (int s = 1; s <= 20; ++s) {
    o.seed = static_cast<uint64_t>(s);
    const CsrMatrix m = f.Rows(o);
    double sum = 0;
    for (float x : m.RowValues(lamp)) sum += x;
    EXPECT_NEAR(sum, 1, 1e-5) << "seed " << s;
  }
}

}  // namespace
}  // namespace radflux
