// Light sampling of the emitter columns (LightTree, LightSampler, monte_carlo's rows):
// the tree's choice probabilities against its own sampling, the estimate's expectation
// against closed forms over many seeds (within a stated confidence bound), and the cost
// per row in rays, which must not grow with the number of emitter patches.
#include "solver/formfactor/light_sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <span>
#include <vector>

#include "howell_closed_forms.h"
#include "solver/formfactor/light_tree.h"
#include "solver/formfactor/row_rays.h"
#include "test_scenes.h"

namespace radflux {
namespace {

using testing::MeanOverSeeds;
using testing::ObjQuad;
using testing::QuadGrid;
using testing::RowFixture;
using testing::SceneFromObj;
using testing::SeedMean;

// A g x g grid of emitter faces ("black": Kd 0, Ke 1) over [-0.5, 0.5]^2 at height z,
// facing down; as two triangles per cell when `triangles`; each face shrunk about its cell's
// centre to `fill` of the cell's side (1: they tile the square).
std::string EmitterGrid(int g, double z, bool triangles, int& next, double fill = 1) {
  std::string obj;
  const double half = 0.5 * fill / g;
  for (int a = 0; a < g; ++a) {
    for (int b = 0; b < g; ++b) {
      const double cx = -0.5 + (a + 0.5) / g, cy = -0.5 + (b + 0.5) / g;
      const double x0 = fill == 1 ? -0.5 + double(a) / g : cx - half;
      const double x1 = fill == 1 ? -0.5 + double(a + 1) / g : cx + half;
      const double y0 = fill == 1 ? -0.5 + double(b) / g : cy - half;
      const double y1 = fill == 1 ? -0.5 + double(b + 1) / g : cy + half;
      const std::string name = "lamp" + std::to_string(a) + "_" + std::to_string(b);
      const Vec3 p00{x0, y0, z}, p01{x0, y1, z}, p11{x1, y1, z}, p10{x1, y0, z};
      if (triangles) {
        obj += ObjQuad(name + "a", "black", {p00, p01, p11}, next);
        obj += ObjQuad(name + "b", "black", {p00, p11, p10}, next);
      } else {
        obj += ObjQuad(name, "black", {p00, p01, p11, p10}, next);
      }
    }
  }
  return obj;
}

// The unit square "receiver" (white, at z = 0, facing up) under EmitterGrid(g, z, ...).
std::string ReceiverUnderGrid(int g, double z, bool triangles, int& next, double fill = 1) {
  std::string obj =
      ObjQuad("receiver", "white", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  return obj + EmitterGrid(g, z, triangles, next, fill);
}

// Sum over the emitter columns of row `i`.
double EmitterRowSum(const RowFixture& f, const CsrMatrix& m, uint32_t i) {
  const auto cols = m.RowCols(i);
  const auto vals = m.RowValues(i);
  double sum = 0;
  for (size_t k = 0; k < cols.size(); ++k) sum += f.context.emitter[cols[k]] ? vals[k] : 0;
  return sum;
}

// The receiver's estimated form factor to all emitters over `seeds` seeds.
SeedMean EmitterFormFactorOverSeeds(RowFixture& f, const std::string& receiver, int seeds) {
  uint32_t row = 0;
  while (f.ObjectOf(row) != receiver) ++row;
  FormFactorOptions o;
  o.rays = 4;     // the non-emitter rays play no part here
  o.samples = 4;  // 4 points, 16 light samples
  o.cutoff = 0;
  return MeanOverSeeds(seeds, [&](uint64_t seed) {
    o.seed = seed;
    return EmitterRowSum(f, f.Rows(o), row);
  });
}

// Unbiased: a unit square under a unit square of emitters one apart, the emitters as one
// face, 20 x 20 rectangles and 20 x 20 x 2 triangles. The mean over 400 seeds is within
// 4 standard errors (a false alarm about once in 16,000 runs, were the code right) of
// Howell's closed form, and the standard error itself is below 1% of it.
TEST(LightSampling, ExpectedEmitterFormFactorIsTheClosedForm) {
  const double exact = testing::ParallelRectangles(1, 1, 1);
  for (auto [g, triangles] : {std::pair{1, false}, {20, false}, {20, true}}) {
    int next = 1;
    RowFixture f(SceneFromObj(ReceiverUnderGrid(g, 1, triangles, next)), MeshOptions{});
    const SeedMean m = EmitterFormFactorOverSeeds(f, "receiver", 400);
    std::printf("  %d x %d %s: %.5f +- %.5f (exact %.5f)\n", g, g,
                triangles ? "triangle pairs" : "rectangles", m.mean, m.standard_error, exact);
    EXPECT_NEAR(m.mean, exact, 4 * m.standard_error + 1e-12);
    EXPECT_LT(m.standard_error, 0.01 * exact);
  }
}

// Near field: the same squares 0.05 apart (a reflector just under a lamp), where F_ij(x)
// runs from about 0.25 at the receiver's corners to 0.9 at its centre. Still unbiased (mean
// over 100 seeds within 4 standard errors of Howell's closed form), and one row's estimate
// spreads by under 1% of F (a standard deviation of 6.1% with 4 points and no near-field
// factor; 0.64% with 16 x 4 points of 16 samples, 0.25% with 16 x 16 points of 4).
TEST(LightSampling, ReceiverNearAnEmitterTakesMorePoints) {
  const double exact = testing::ParallelRectangles(1, 1, 0.05);
  int next = 1;
  RowFixture f(SceneFromObj(ReceiverUnderGrid(1, 0.05, false, next)), MeshOptions{});
  const int seeds = 100;
  const SeedMean m = EmitterFormFactorOverSeeds(f, "receiver", seeds);
  const double spread = m.standard_error * std::sqrt(double(seeds));
  std::printf("  0.05 apart: %.5f +- %.5f (exact %.5f), one row's spread %.4f of F\n", m.mean,
              m.standard_error, exact, spread / exact);
  EXPECT_NEAR(m.mean, exact, 4 * m.standard_error + 1e-12);
  EXPECT_LT(spread, 0.01 * exact);
}

// The same receiver and lamp beside a 10 x 10 floor 20 below, facing up: the receiver's row
// has a fiftieth of the mean row's area, so its near-field points follow its area
// (RowNearFieldFactor: 1 here, 16 above) and it casts its 16 cosine rays and 64 light samples,
// not 1,024 (RenderPark's corridor: the slots over its lamps and the ceiling beside them, 60%
// of its rays). Still unbiased (100 seeds, within 4 standard errors of Howell's closed form).
TEST(LightSampling, SmallRowNearAnEmitterTakesPointsByItsArea) {
  const double exact = testing::ParallelRectangles(1, 1, 0.05);
  int next = 1;
  std::string obj = ReceiverUnderGrid(1, 0.05, false, next);
  obj += ObjQuad("floor", "white", {{-5, -5, -20}, {5, -5, -20}, {5, 5, -20}, {-5, 5, -20}}, next);
  RowFixture f(SceneFromObj(obj), MeshOptions{});
  uint32_t receiver = 0;
  while (f.ObjectOf(receiver) != "receiver") ++receiver;
  FormFactorOptions o;
  o.rays = 64;
  o.samples = 4;
  o.cutoff = 0;
  const auto builder = MakeRowBuilder(f.context, o);
  RowAccumulator row(f.mesh.size());
  const uint64_t rays = builder->BuildRow(receiver, row);
  std::printf("  receiver's row: %llu rays\n", static_cast<unsigned long long>(rays));
  EXPECT_EQ(rays, static_cast<uint64_t>(kLeastRowRays + kLightSamplesPerS * o.samples));
  const SeedMean m = EmitterFormFactorOverSeeds(f, "receiver", 100);
  std::printf("  0.05 apart, a small row: %.5f +- %.5f (exact %.5f)\n", m.mean, m.standard_error,
              exact);
  EXPECT_NEAR(m.mean, exact, 4 * m.standard_error + 1e-12);
}

// Grazing: a wall strip just below the edge of a lamp, beside it (the Cornell box's wall tops,
// lit from the lamp's plane at grazing angles on both sides): a unit square of emitters at
// z = 1 facing down and a receiver 0.1 high on the plane x = 0.5 facing it, from 0.02 to 0.12
// below the lamp's plane. Unbiased there too: the mean over 400 seeds within 4 standard errors
// of Howell's C-14 (perpendicular rectangles with a common edge) taken as the difference of
// two receivers from the edge down. Cycles' reference pictures are 1-2% below this closed
// form on the Cornell wall tops; radflux must not drift towards them.
TEST(LightSampling, GrazingStripBesideALampIsTheClosedForm) {
  const double gap = 0.02, height = 0.1;
  const auto from_edge = [](double h) { return h * testing::PerpendicularRectangles(h, 1, 1); };
  const double exact = (from_edge(gap + height) - from_edge(gap)) / height;
  const double top = 1 - gap, bottom = top - height;
  int next = 1;
  std::string obj =
      ObjQuad("receiver", "white",
              {{.5, .5, bottom}, {.5, -.5, bottom}, {.5, -.5, top}, {.5, .5, top}}, next);
  obj += EmitterGrid(1, 1, false, next);
  RowFixture f(SceneFromObj(obj), MeshOptions{});
  const SeedMean m = EmitterFormFactorOverSeeds(f, "receiver", 400);
  std::printf("  grazing strip: %.6f +- %.6f (exact %.6f)\n", m.mean, m.standard_error, exact);
  EXPECT_NEAR(m.mean, exact, 4 * m.standard_error + 1e-12);
  EXPECT_LT(m.standard_error, 0.01 * exact);
}

// With an occluder: a plate over x > 0 half-way between the squares blocks exactly half of
// the exchange (the symmetry (p, q) -> (-p, -q)). A ratio estimator (unoccluded form factor
// times a visible fraction) is biased here; the light samples must not be.
TEST(LightSampling, HalfPlaneOccluderHalvesTheExpectedFormFactor) {
  int next = 1;
  std::string obj = ReceiverUnderGrid(4, 1, false, next);
  obj += ObjQuad("wall", "white", {{0, -1, .5}, {1, -1, .5}, {1, 1, .5}, {0, 1, .5}}, next);
  RowFixture f(SceneFromObj(obj), MeshOptions{});
  const SeedMean m = EmitterFormFactorOverSeeds(f, "receiver", 400);
  const double exact = testing::ParallelRectangles(1, 1, 1) / 2;
  std::printf("  half occluded: %.5f +- %.5f (exact %.5f)\n", m.mean, m.standard_error, exact);
  EXPECT_NEAR(m.mean, exact, 4 * m.standard_error);
  EXPECT_LT(m.standard_error, 0.02 * exact);
}

// The far-field importance (the integrand's mean over the corners) against the exact one
// (Lambert's form factor) for a unit square and a triangle facing down, from 2,000 random
// points 4 to 8 radii from the centre with random normals: zero exactly where the exact one
// is (else an emitter that can light x could get probability 0: bias), and never below 0.7
// of it (0.82 measured for the square, 0.76 for the triangle): a far node is never much
// less likely than its share, the heavy tail's cause. Where every corner is in front at
// most 1.5 times (1.30, 1.39 measured); where x's tangent plane cuts the polygon it can be
// far above a sliver's exact value, which only takes probability from the others.
TEST(LightSampling, FarImportanceIsZeroWhereTheExactIsAndCloseBeyond) {
  EmitterShape square;
  square.corner = {Vec3{-.5, -.5, 1}, Vec3{-.5, .5, 1}, Vec3{.5, .5, 1}, Vec3{.5, -.5, 1}};
  square.corners = 4;
  EmitterShape triangle = square;
  triangle.corner[3] = triangle.corner[2];
  triangle.corners = 3;
  uint32_t state = 12345;
  const auto uniform = [&] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * 0x1p-24;
  };
  const auto direction = [&] {
    const double z = 2 * uniform() - 1, phi = 2 * std::numbers::pi * uniform();
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return Vec3{r * std::cos(phi), r * std::sin(phi), z};
  };
  for (EmitterShape* shape : {&square, &triangle}) {
    shape->normal = {0, 0, -1};
    shape->area = shape->corners == 4 ? 1 : 0.5;
    shape->power = 2 * shape->area;
    SetEmitterBounds(*shape);
    const std::span<const Vec3> corners(shape->corner.data(), shape->corners);
    double lowest = INFINITY, highest_in_front = 0;
    for (int k = 0; k < 2000; ++k) {
      const Vec3 x = shape->centre + direction() * (shape->radius * (4 + 4 * uniform()));
      const Vec3 n = direction();
      const double exact = EmitterImportance(*shape, x, n);
      const double far = FarEmitterImportance(corners, shape->normal, shape->power, x, n);
      ASSERT_EQ(exact > 0, far > 0) << k;
      if (!(exact > 0)) continue;
      lowest = std::min(lowest, far / exact);
      bool all_front = true;
      for (const Vec3& c : corners) all_front = all_front && Dot(c - x, n) > 0;
      if (all_front) highest_in_front = std::max(highest_in_front, far / exact);
    }
    std::printf("  %u corners: far / exact >= %.3f, <= %.3f with every corner in front\n",
                shape->corners, lowest, highest_in_front);
    EXPECT_GE(lowest, 0.7);
    EXPECT_LE(highest_in_front, 1.5);
  }
}

// Choose picks each emitter as often as Probability says (4,096 stratified u: the
// frequencies are exact to a stratum or two), every emitter that can light the receiver has
// a probability above 0, and the probabilities sum to at most 1: a walk may end at a leaf
// pair that cannot light the receiver although their node's bound said it might (that
// sample is lost, not biased), but rarely (below 10% here, where a third of the emitters
// lie behind the tilted receiver's horizon). The lamps have gaps between them (no node is
// tiled), so every choice walks to one emitter.
TEST(LightSampling, TreeChoosesWithTheProbabilityItStates) {
  int next = 1;
  RowFixture f(SceneFromObj(EmitterGrid(6, 1, false, next, 0.8)), MeshOptions{});
  std::vector<EmitterShape> shapes;
  for (uint32_t j = 0; j < f.mesh.size(); ++j) shapes.push_back(MakeEmitterShape(f.mesh, j, 1));
  const LightTree tree(shapes);
  for (const auto& [x, n] : {std::pair{Vec3{0, 0, 0}, Vec3{0, 0, 1}},
                             {Vec3{0.4, -0.3, 0.7}, Normalize(Vec3{1, 0, 1})},
                             {Vec3{2, 0, 0.5}, Vec3{-1, 0, 0}}}) {
    double total = 0, lost = 0;
    std::map<uint32_t, double> frequency;  // of each chosen node
    const int count = 4096;
    const LightTree::Cut cut = tree.CutAt(x, n);
    for (int s = 0; s < count; ++s) {
      const auto c = tree.Choose(cut, x, n, (s + 0.5) / count);
      if (!c) {
        lost += 1.0 / count;
        continue;
      }
      ASSERT_TRUE(tree.IsLeaf(c->node));
      const uint32_t k = *tree.Locate(c->node, Vec3{});
      EXPECT_NEAR(c->probability, tree.Probability(cut, x, n, k), 1e-12);
      frequency[c->node] += 1.0 / count;
    }
    for (uint32_t k = 0; k < shapes.size(); ++k) {
      ASSERT_TRUE(tree.IsLeaf(tree.Sampled(k)));
      const double p = tree.Probability(cut, x, n, k);
      total += p;
      if (EmitterImportance(shapes[k], x, n) > 0) {
        EXPECT_GT(p, 0) << k;
      }
      EXPECT_NEAR(frequency[tree.Sampled(k)], p, 2.0 / count) << k;
    }
    EXPECT_LE(total, 1 + 1e-12);
    EXPECT_NEAR(lost, 1 - total, 4.0 / count);
    EXPECT_GT(total, 0.9);
  }
}

// Emitters that tile a rectangle (a 6 x 6 grid of quads, or of triangle pairs) are one
// sampled node, the rectangle, whatever the receiver: Choose always returns it with
// probability 1, and Locate credits each point of the rectangle to the face that holds it
// (every cell's centre and points near its corners; a point off the rectangle to none).
TEST(LightSampling, TiledEmittersAreSampledAsTheirRectangle) {
  for (const bool triangles : {false, true}) {
    int next = 1;
    RowFixture f(SceneFromObj(EmitterGrid(6, 1, triangles, next)), MeshOptions{});
    std::vector<EmitterShape> shapes;
    for (uint32_t j = 0; j < f.mesh.size(); ++j) shapes.push_back(MakeEmitterShape(f.mesh, j, 1));
    const LightTree tree(shapes);
    const uint32_t root = tree.Sampled(0);
    EXPECT_FALSE(tree.IsLeaf(root));
    EXPECT_NEAR(tree.Shape(root).area, 1, 1e-12);
    for (uint32_t k = 0; k < shapes.size(); ++k) EXPECT_EQ(tree.Sampled(k), root) << k;
    for (const Vec3& x : {Vec3{0, 0, 0}, Vec3{0.45, -0.3, 0.9}}) {
      const LightTree::Cut cut = tree.CutAt(x, {0, 0, 1});
      const auto c = tree.Choose(cut, x, {0, 0, 1}, 0.7);
      ASSERT_TRUE(c);
      EXPECT_EQ(c->node, root);
      EXPECT_DOUBLE_EQ(c->probability, 1);
    }
    for (uint32_t k = 0; k < shapes.size(); ++k) {
      const EmitterShape& e = shapes[k];
      Vec3 centre;
      for (uint32_t m = 0; m < e.corners; ++m) centre += e.corner[m] / e.corners;
      for (uint32_t m = 0; m < e.corners; ++m) {
        const Vec3 p = centre + (e.corner[m] - centre) * (m == 0 ? 0.0 : 0.98);
        const auto lit = tree.Locate(root, p);
        ASSERT_TRUE(lit) << k;
        EXPECT_EQ(*lit, k) << k << " " << m;
      }
    }
    EXPECT_FALSE(tree.Locate(root, {0.6, 0, 1}));
  }
}

// Row 0's entries, column by column, as mean and standard error over `seeds` seeds of `o`.
std::vector<SeedMean> FirstRowOverSeeds(RowFixture& f, FormFactorOptions o, int seeds) {
  std::vector<double> sum(f.mesh.size(), 0), sum2(f.mesh.size(), 0);
  for (int s = 1; s <= seeds; ++s) {
    o.seed = static_cast<uint64_t>(s);
    const CsrMatrix m = f.Rows(o);
    const auto cols = m.RowCols(0);
    const auto vals = m.RowValues(0);
    for (size_t k = 0; k < cols.size(); ++k) {
      sum[cols[k]] += vals[k], sum2[cols[k]] += vals[k] * vals[k];
    }
  }
  std::vector<SeedMean> column(f.mesh.size());
  for (size_t j = 0; j < column.size(); ++j) {
    const double mean = sum[j] / seeds;
    column[j] = {mean, std::sqrt(std::max(0.0, sum2[j] / seeds - mean * mean) / (seeds - 1))};
  }
  return column;
}

// Each emitter of a tiled plane gets its own form factor, not a share of the plane's: a unit
// square under a 2 x 2 grid of emitters at distance c sees each quarter with F / 4
// (symmetry), F Howell's closed form; the mean of each column over 400 seeds is within 4
// standard errors. At c = 1 (F = 0.2) the light samples' directions are cosine-weighted
// within the rectangle, at c = 4 (F = 0.018) drawn in its solid angle.
TEST(LightSampling, TiledEmittersEachGetTheirOwnFormFactor) {
  for (const double c : {1.0, 4.0}) {
    const double exact = testing::ParallelRectangles(1, 1, c) / 4;
    int next = 1;
    RowFixture f(SceneFromObj(ReceiverUnderGrid(2, c, false, next)), MeshOptions{});
    ASSERT_EQ(f.ObjectOf(0), "receiver");
    FormFactorOptions o;
    o.rays = 4;
    o.samples = 4;
    o.cutoff = 0;
    const std::vector<SeedMean> column = FirstRowOverSeeds(f, o, 400);
    for (uint32_t j = 1; j < f.mesh.size(); ++j) {
      const double mean = column[j].mean, error = column[j].standard_error;
      std::printf("  c = %g, quarter %u: %.6f +- %.6f (exact %.6f)\n", c, j, mean, error, exact);
      EXPECT_NEAR(mean, exact, 4 * error + 1e-12);
      EXPECT_LT(error, 0.02 * exact);
    }
  }
}

// F from rectangle [x0, x1] x [y0, y1] to the parallel rectangle [xi0, xi1] x [eta0, eta1] at
// distance z, facing each other, at any offset (Howell C-12, as summed by Ehlert and Smith
// 1993; reproduces C-11, ParallelRectangles, when aligned: checked below).
double OffsetParallelRectangles(std::array<double, 2> x, std::array<double, 2> y,
                                std::array<double, 2> xi, std::array<double, 2> eta, double z) {
  const auto g = [z](double u, double v) {
    const double a = std::sqrt(u * u + z * z), b = std::sqrt(v * v + z * z);
    return (v * a * std::atan(v / a) + u * b * std::atan(u / b) -
            z * z / 2 * std::log(u * u + v * v + z * z)) /
           (2 * std::numbers::pi);
  };
  double sum = 0;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 2; ++k) {
        for (int l = 0; l < 2; ++l) {
          sum += ((i + j + k + l) % 2 ? -1 : 1) * g(x[i] - xi[k], y[j] - eta[l]);
        }
      }
    }
  }
  return sum / ((x[1] - x[0]) * (y[1] - y[0]));
}

// Separate panels (a 5 x 5 grid of squares at 0.8 of their cells' side, gaps between: no
// node is tiled, each light sample walks the tree, below far nodes by FarEmitterImportance)
// one above a unit square: each panel's column, averaged over 400 seeds, is within 4
// standard errors of its own closed form (C-12 at its offset; worst 1.85 measured), and its
// standard error below 5% of it (3.6% at the corner panels).
TEST(LightSampling, SeparatePanelsEachGetTheirOwnFormFactor) {
  EXPECT_NEAR(OffsetParallelRectangles({-.5, .5}, {-.5, .5}, {-.5, .5}, {-.5, .5}, 1),
              testing::ParallelRectangles(1, 1, 1), 1e-12);
  const int g = 5;
  const double fill = 0.8;
  int next = 1;
  RowFixture f(SceneFromObj(ReceiverUnderGrid(g, 1, false, next, fill)), MeshOptions{});
  ASSERT_EQ(f.ObjectOf(0), "receiver");
  ASSERT_EQ(f.mesh.size(), 1u + g * g);
  FormFactorOptions o;
  o.rays = 4;
  o.samples = 4;
  o.cutoff = 0;
  const std::vector<SeedMean> column = FirstRowOverSeeds(f, o, 400);
  double worst = 0;  // in standard errors
  for (uint32_t j = 1; j < f.mesh.size(); ++j) {
    const EmitterShape panel = MakeEmitterShape(f.mesh, j, 1);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const Vec3& c : panel.corner) {
      x0 = std::min(x0, c.x), x1 = std::max(x1, c.x), y0 = std::min(y0, c.y),
      y1 = std::max(y1, c.y);
    }
    const double exact = OffsetParallelRectangles({-.5, .5}, {-.5, .5}, {x0, x1}, {y0, y1}, 1);
    const double mean = column[j].mean, error = column[j].standard_error;
    worst = std::max(worst, std::abs(mean - exact) / error);
    EXPECT_NEAR(mean, exact, 4 * error + 1e-12) << "panel " << j;
    EXPECT_LT(error, 0.05 * exact) << "panel " << j;
  }
  std::printf("  %d separate panels: worst |mean - exact| %.2f standard errors\n", g * g, worst);
}

// Wall lamps as in the conference room: a row of 24 box fixtures (0.3 wide, 0.1 high, 0.1
// deep, every face emitting outwards) 0.18 in front of a wall at z = 0, and a 12 x 12 grid of
// ceiling panels (0.3 square, facing down) over the room. Seen from the wall, the exact share
// of a lamp's contribution among all emitters' is F_j(x) / sum_k F_k(x) (equal exitances);
// a light sample of lamp j weighs F_j(x) / P(j | x). Over a grid of wall points behind and
// between the lamps, that weight stays within 4 times sum_k F_k(x) for every emitter that can
// light the point (choosing in proportion to F_j would give exactly 1 times; 2.6 measured).
// Through the plain tree walk (a cut of just the root) it reaches 30 times here, and in the
// conference room samples weighed 1,400 times F: a heavy tail that made one seed's picture
// 85% too bright on the floor.
TEST(LightSampling, WallBesideLampsIsNotAHeavyTail) {
  int next = 1;
  std::string obj;
  for (int k = 0; k < 24; ++k) {
    const double x0 = -6 + 0.5 * k, x1 = x0 + 0.3, y0 = 2.2, y1 = 2.3, z0 = -0.28, z1 = -0.18;
    const std::string name = "fixture" + std::to_string(k);
    // Counter-clockwise seen from outside: the front (+z, facing the wall), back, ends, top
    // and bottom.
    obj += ObjQuad(name, "black", {{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, next);
    obj += ObjQuad(name, "black", {{x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}}, next);
    obj += ObjQuad(name, "black", {{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}}, next);
    obj += ObjQuad(name, "black", {{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}, next);
    obj += ObjQuad(name, "black", {{x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}}, next);
    obj += ObjQuad(name, "black", {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}, next);
  }
  for (int a = 0; a < 12; ++a) {
    for (int b = 0; b < 12; ++b) {
      const double x0 = -6 + a, z0 = -12 + b, y = 3;
      obj += ObjQuad("panel", "black",
                     {{x0, y, z0}, {x0 + 0.3, y, z0}, {x0 + 0.3, y, z0 + 0.3}, {x0, y, z0 + 0.3}},
                     next);
    }
  }
  RowFixture f(SceneFromObj(obj), MeshOptions{});
  std::vector<EmitterShape> shapes;
  for (uint32_t j = 0; j < f.mesh.size(); ++j) shapes.push_back(MakeEmitterShape(f.mesh, j, 1));
  ASSERT_EQ(shapes.size(), 24u * 6 + 144);
  const LightTree tree(shapes);
  const Vec3 n{0, 0, -1};
  double worst = 0;
  for (int a = 0; a < 60; ++a) {
    for (int b = 0; b < 12; ++b) {
      const Vec3 x{-6.05 + 0.2 * a, 2.0 + 0.04 * b, 0};
      const LightTree::Cut cut = tree.CutAt(x, n);
      double total = 0;
      for (const EmitterShape& s : shapes) total += EmitterFormFactor(s, x, n);
      ASSERT_GT(total, 0);
      for (uint32_t k = 0; k < shapes.size(); ++k) {
        const double form_factor = EmitterFormFactor(shapes[k], x, n);
        if (!(form_factor > 0)) continue;
        const double p = tree.Probability(cut, x, n, k);
        ASSERT_GT(p, 0) << k;
        worst = std::max(worst, form_factor / p / total);
      }
    }
  }
  std::printf("  worst F_j / P(j) against sum F: %.3g\n", worst);
  EXPECT_LT(worst, 4);
}

// Two-sided lamps as in RenderPark's corridor (MGF: each side lit on its own): 8 x 4 lamps,
// 0.4 square, 2 cm under a ceiling at z = 10, each a face lit downwards and its twin at the
// same place lit upwards. From points on a wall beside them, the floor and the ceiling, a light
// sample of lamp j weighs F_j(x) / P(j | x); it stays within 2 times sum_k F_k(x) for every
// lamp that can light the point (1.2 measured). A tree that kept each lamp's twins together
// faced both ways at every node above them (no cosine bound, no culling) and weighed samples
// up to 5.5 times sum F: the corridor's walls and floor read 5 times noisier.
TEST(LightSampling, TwoSidedLampsAreChosenByTheSideThatLights) {
  int next = 1;
  std::string obj;
  for (int a = 0; a < 8; ++a) {
    for (int b = 0; b < 4; ++b) {
      const double x0 = -4.2 + 2.5 * a, y0 = -0.2 + 2.5 * b, z = 9.98;
      const Vec3 p00{x0, y0, z}, p10{x0 + 0.4, y0, z}, p11{x0 + 0.4, y0 + 0.4, z},
          p01{x0, y0 + 0.4, z};
      const std::string name = "lamp" + std::to_string(a) + "_" + std::to_string(b);
      obj += ObjQuad(name + "down", "black", {p00, p01, p11, p10}, next);
      obj += ObjQuad(name + "up", "black", {p00, p10, p11, p01}, next);
    }
  }
  RowFixture f(SceneFromObj(obj), MeshOptions{});
  std::vector<EmitterShape> shapes;
  for (uint32_t j = 0; j < f.mesh.size(); ++j) shapes.push_back(MakeEmitterShape(f.mesh, j, 1));
  ASSERT_EQ(shapes.size(), 64u);
  const LightTree tree(shapes);
  struct Receiver {
    Vec3 x, n;
  };
  std::vector<Receiver> receivers;
  for (int a = 0; a < 40; ++a) {
    for (int b = 0; b < 10; ++b) {
      receivers.push_back({{-5, -1 + 0.25 * a, 0.5 + 0.95 * b}, {1, 0, 0}});    // a wall
      receivers.push_back({{-5 + 0.5 * a, -1 + 0.9 * b, 0}, {0, 0, 1}});        // the floor
      receivers.push_back({{-4.9 + 0.5 * a, -0.9 + 0.9 * b, 10}, {0, 0, -1}});  // the ceiling
    }
  }
  double worst = 0;
  for (const Receiver& r : receivers) {
    const LightTree::Cut cut = tree.CutAt(r.x, r.n);
    double total = 0;
    for (const EmitterShape& s : shapes) total += EmitterFormFactor(s, r.x, r.n);
    if (!(total > 0)) continue;
    for (uint32_t k = 0; k < shapes.size(); ++k) {
      const double form_factor = EmitterFormFactor(shapes[k], r.x, r.n);
      if (!(form_factor > 0)) continue;
      const double p = tree.Probability(cut, r.x, r.n, k);
      ASSERT_GT(p, 0) << k;
      worst = std::max(worst, form_factor / p / total);
    }
  }
  std::printf("  worst F_j / P(j) against sum F: %.3g\n", worst);
  EXPECT_LT(worst, 2);
}

// A closed unit room whose ceiling emits, as 1 face or as 64 x 64 = 4,096 faces (walls and
// floor 8 x 8 faces each; every face one patch). Every row casts the same rays in both: k
// cosine rays and 16 s light samples, times the near-field factor of the wall patches that
// touch the ceiling (8 or 9 here: (size / distance)^2) and at most 16; and the rows still sum
// to 1 (the room is closed): the cost per row does not grow with the number of emitter
// patches, and the estimate stays a form-factor row.
TEST(LightSampling, CostPerRowDoesNotGrowWithEmitterPatches) {
  FormFactorOptions o;
  o.rays = 64;
  o.samples = 4;
  o.cutoff = 0;
  const uint64_t far_budget = static_cast<uint64_t>(o.rays + kLightSamplesPerS * o.samples);
  const uint64_t budget = static_cast<uint64_t>(o.rays + 16 * kLightSamplesPerS * o.samples);
  std::vector<uint64_t> one_emitter_rays;  // per row, with the ceiling as one face
  for (int g : {1, 64}) {
    int next = 1;
    std::string obj;
    obj += QuadGrid("floor", "white", {-.5, -.5, 0}, {1, 0, 0}, {0, 1, 0}, 8, next);
    obj += QuadGrid("x0", "white", {-.5, -.5, 0}, {0, 1, 0}, {0, 0, 1}, 8, next);
    obj += QuadGrid("x1", "white", {.5, -.5, 0}, {0, 0, 1}, {0, 1, 0}, 8, next);
    obj += QuadGrid("y0", "white", {-.5, -.5, 0}, {0, 0, 1}, {1, 0, 0}, 8, next);
    obj += QuadGrid("y1", "white", {-.5, .5, 0}, {1, 0, 0}, {0, 0, 1}, 8, next);
    obj += QuadGrid("ceiling", "black", {-.5, -.5, 1}, {0, 1, 0}, {1, 0, 0}, g, next);
    RowFixture f(SceneFromObj(obj), MeshOptions{});
    const auto builder = MakeRowBuilder(f.context, o);
    RowAccumulator row(f.mesh.size());
    RowBlock block;
    uint64_t rays = 0, rows = 0, emitters = 0;
    double worst_sum = 0;
    for (uint32_t i = 0; i < f.mesh.size(); ++i) {
      emitters += f.context.emitter[i];
      if (f.context.emitter[i]) continue;
      const uint64_t r = builder->BuildRow(i, row);
      EXPECT_LE(r, budget) << "row " << i << " with " << g * g << " emitter faces";
      if (g == 1) one_emitter_rays.push_back(r);
      if (g > 1 && rows < one_emitter_rays.size()) {
        EXPECT_LE(r, one_emitter_rays[rows]) << "row " << i << " with 4,096 emitter faces";
      }
      double sum = 0;
      for (uint32_t j : row.Touched()) sum += row.Value(j);
      worst_sum = std::max(worst_sum, std::abs(sum - 1));
      row.Flush(0, block);
      rays += r;
      ++rows;
    }
    ASSERT_EQ(emitters, static_cast<uint64_t>(g * g));
    const double mean_rays = double(rays) / double(rows);
    std::printf("  %d emitter patches: %.2f rays per row, worst |row sum - 1| %.3f\n", g * g,
                mean_rays, worst_sum);
    EXPECT_GT(mean_rays, 0.95 * double(far_budget));
    // A row's sum: the noise of 64 cosine rays (binomial, a standard deviation of at most
    // 0.06) plus the light samples' spread; 0.3 is about 5 standard deviations.
    EXPECT_LT(worst_sum, 0.3);
  }
}

}  // namespace
}  // namespace radflux
