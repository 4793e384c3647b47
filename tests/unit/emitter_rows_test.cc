// Monte Carlo rows of emitting patches (lamps with Kd > 0 have rows too), their cosine rays
// alone, emitter columns included (monte_carlo.cc): Howell's closed forms between two
// emitters at close range, and a closed box of emitters whose every row sums to 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "howell_closed_forms.h"
#include "test_scenes.h"

namespace radflux {
namespace {

using testing::MeanOverSeeds;
using testing::ObjQuad;
using testing::QuadGrid;
using testing::RowFixture;
using testing::SceneFromObj;
using testing::SeedMean;

// The area-weighted form factor from object `from` to `to` over `seeds` seeds at the
// default options (no cut-off).
SeedMean SurfaceFormFactorOverSeeds(RowFixture& f, const std::string& from, const std::string& to,
                                    int seeds) {
  FormFactorOptions o;
  o.cutoff = 0;
  return MeanOverSeeds(seeds, [&](uint64_t seed) {
    o.seed = seed;
    return f.SurfaceFormFactor(f.Rows(o), from, to);
  });
}

void ExpectClosedForm(RowFixture& f, const std::string& from, const std::string& to, double exact) {
  const SeedMean m = SurfaceFormFactorOverSeeds(f, from, to, 16);
  std::printf("  F(%s -> %s) %.5f +- %.5f (exact %.5f)\n", from.c_str(), to.c_str(), m.mean,
              m.standard_error, exact);
  EXPECT_NEAR(m.mean, exact, 4 * m.standard_error + 1e-12);
  EXPECT_NEAR(m.mean, exact, 0.01 * exact);
}

// Howell C-14: a lamp floor (1 x 1.3) and a lamp wall (0.7 x 1.3) sharing an edge, 8 x 8
// patches each: the patches along the edge see the other lamp filling up to half their
// hemisphere, where cosine rays and light samples are combined. Both directions, each
// within 4 standard errors of the mean over 16 seeds and within 1%.
TEST(EmitterRows, PerpendicularLampsSharingAnEdgeMatchHowell) {
  int next = 1;
  std::string obj = ObjQuad("a", "lamp", {{0, 0, 0}, {1, 0, 0}, {1, 1.3, 0}, {0, 1.3, 0}}, next);
  obj += ObjQuad("b", "lamp", {{0, 0, 0}, {0, 1.3, 0}, {0, 1.3, 0.7}, {0, 0, 0.7}}, next);
  RowFixture f(SceneFromObj(obj), MeshOptions{128, 0});
  ExpectClosedForm(f, "a", "b", testing::PerpendicularRectangles(1, 0.7, 1.3));
  ExpectClosedForm(f, "b", "a", testing::PerpendicularRectangles(0.7, 1, 1.3));
}

// Howell C-11: two lamp squares 0.1 apart (F = 0.82), 4 x 4 patches each.
TEST(EmitterRows, ParallelLampsAtCloseRangeMatchHowell) {
  int next = 1;
  std::string obj =
      ObjQuad("a", "lamp", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += ObjQuad("b", "lamp", {{-.5, -.5, .1}, {-.5, .5, .1}, {.5, .5, .1}, {.5, -.5, .1}}, next);
  RowFixture f(SceneFromObj(obj), MeshOptions{32, 0});
  ExpectClosedForm(f, "a", "b", testing::ParallelRectangles(1, 1, 0.1));
}

// A closed unit box whose ceiling and four walls are lamps (4 x 4 faces each) over a white
// floor, with a lamp bar (a closed solid, 0.4 x 0.05 x 0.4, every face emitting outwards)
// 0.02 in front of one wall: emitter patches beside other emitters, facing them and facing
// solid geometry at close range. Every row sums to 1 in expectation: the mean over 16 seeds
// of each surface's rows is within 4 standard errors of 1 and within 0.5%. And the lamps'
// rows (walls, ceiling and bar, where the other lamps fill 80% of the hemisphere) are their
// cosine rays alone, every one a hit: each sums to 1 up to float rounding (with light
// samples for the lamps' columns they spread by a standard deviation of 0.042).
TEST(EmitterRows, ClosedBoxOfLampsRowsSumToOne) {
  int next = 1;
  std::string obj;
  obj += QuadGrid("floor", "white", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4, next);
  obj += QuadGrid("ceiling", "lamp", {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, 4, next);
  obj += QuadGrid("walls", "lamp", {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 4, next);
  obj += QuadGrid("walls", "lamp", {1, 0, 0}, {0, 0, 1}, {0, 1, 0}, 4, next);
  obj += QuadGrid("walls", "lamp", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 4, next);
  obj += QuadGrid("walls", "lamp", {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, 4, next);
  // The bar [0.3, 0.7] x [0.93, 0.98] x [0.3, 0.7], faces outwards.
  const Vec3 lo{0.3, 0.93, 0.3}, ex{0.4, 0, 0}, ey{0, 0.05, 0}, ez{0, 0, 0.4};
  obj += QuadGrid("bar", "lamp", lo, ey, ex, 2, next);
  obj += QuadGrid("bar", "lamp", lo + ez, ex, ey, 2, next);
  obj += QuadGrid("bar", "lamp", lo, ex, ez, 2, next);
  obj += QuadGrid("bar", "lamp", lo + ey, ez, ex, 2, next);
  obj += QuadGrid("bar", "lamp", lo, ez, ey, 2, next);
  obj += QuadGrid("bar", "lamp", lo + ex, ey, ez, 2, next);
  RowFixture f(SceneFromObj(obj), MeshOptions{});
  FormFactorOptions o;
  o.cutoff = 0;
  const int seeds = 16;
  struct Sums {
    double sum = 0, sum2 = 0;
    int rows = 0;
  };
  std::map<std::string, Sums> by_object;
  for (int s = 1; s <= seeds; ++s) {
    o.seed = static_cast<uint64_t>(s);
    const CsrMatrix m = f.Rows(o);
    for (uint32_t i = 0; i < f.mesh.size(); ++i) {
      double sum = 0;
      for (const float v : m.RowValues(i)) sum += v;
      Sums& e = by_object[f.ObjectOf(i)];
      e.sum += sum;
      e.sum2 += sum * sum;
      ++e.rows;
    }
  }
  for (const auto& [name, e] : by_object) {
    const double mean = e.sum / e.rows;
    const double spread = std::sqrt(std::max(0.0, e.sum2 / e.rows - mean * mean));
    const double standard_error = spread / std::sqrt(double(e.rows));
    std::printf("  %-8s %4d rows: mean sum %.4f +- %.4f, spread %.4f\n", name.c_str(),
                e.rows / seeds, mean, standard_error, spread);
    EXPECT_NEAR(mean, 1, 0.005) << name;
    if (name == "floor") {
      EXPECT_NEAR(mean, 1, 4 * standard_error) << name;
    } else {  // lamps: every row exactly 1, up to float rounding
      EXPECT_NEAR(mean, 1, 1e-6) << name;
      EXPECT_LT(spread, 1e-6) << name;
    }
  }
}

}  // namespace
}  // namespace radflux
