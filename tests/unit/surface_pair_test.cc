// Per-pair view-factor integration (surface_pair_integrator.h) against Howell's closed forms,
// shaft culling (shaft_cull.h) and exact visibility (shaft_visibility.h), and whole rows
// (surface_rows.h): reciprocity, closure, and no visibility work for unobstructed pairs.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "howell_closed_forms.h"
#include "solver/core/parallel.h"
#include "solver/core/physical_memory.h"
#include "solver/formfactor/shaft_cull.h"
#include "solver/formfactor/shaft_visibility.h"
#include "solver/formfactor/surface_rows.h"
#include "surface_rows_collect.h"

namespace radflux {
namespace {

SurfaceShape Square(Vec3 origin, Vec3 u, Vec3 v) {
  return MakeSurfaceShape({origin, origin + u, origin + u + v, origin + v});
}

double Exact(const SurfaceShape& i, const SurfaceShape& j, double tolerance = 1e-6) {
  PairIntegration o;
  o.tolerance = tolerance;
  o.max_depth = 10;
  PairCounts counts;
  return UnoccludedViewFactor(i, j, o, counts);
}

TEST(SurfacePair, ParallelDirectlyOpposedRectanglesMatchHowellC11) {
  for (double c : {0.1, 0.5, 1.0, 4.0}) {
    const SurfaceShape a = Square({0, 0, 0}, {1, 0, 0}, {0, 2, 0});   // faces +z
    const SurfaceShape b = Square({0, 0, c}, {0, 2, 0}, {1, 0, 0});   // faces -z
    const double exact = testing::ParallelRectangles(1, 2, c);
    EXPECT_NEAR(Exact(a, b), exact, 2e-5 * exact) << "c = " << c;
    EXPECT_NEAR(Exact(b, a), exact, 2e-5 * exact) << "c = " << c;
  }
}

TEST(SurfacePair, PerpendicularRectanglesWithCommonEdgeMatchHowellC14) {
  for (auto [w, h, l] : {std::array{1.0, 1.0, 1.0}, std::array{0.5, 2.0, 1.0}, std::array{3.0, 1.0, 0.5}}) {
    const SurfaceShape floor = Square({0, 0, 0}, {w, 0, 0}, {0, l, 0});   // faces +z
    const SurfaceShape wall = Square({0, 0, 0}, {0, l, 0}, {0, 0, h});    // faces +x
    const double exact = testing::PerpendicularRectangles(w, h, l);
    EXPECT_NEAR(Exact(floor, wall), exact, 1e-4 * exact) << w << " " << h << " " << l;
  }
}

// Coaxial discs meshed as regular 64-gons: the polygons' own view factor is the discs' to
// within the area lost to the chords (about (pi/64)^2 / 3 of each disc).
TEST(SurfacePair, CoaxialPolygonDiscsMatchHowellC41) {
  const int n = 64;
  std::vector<Vec3> lower, upper;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    lower.push_back({std::cos(t), std::sin(t), 0});
    upper.push_back({0.5 * std::cos(-t), 0.5 * std::sin(-t), 1});
  }
  const double exact = testing::CoaxialDiscs(1, 0.5, 1);
  EXPECT_NEAR(Exact(MakeSurfaceShape(lower), MakeSurfaceShape(upper), 1e-4), exact, 5e-3 * exact);
}

TEST(SurfacePair, FarPairsTakeOnePointAndBackToBackPairsAreCulled) {
  const SurfaceShape a = Square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const SurfaceShape far = Square({0, 0, 20}, {0, 1, 0}, {1, 0, 0});
  const SurfaceShape behind = Square({0, 0, -1}, {1, 0, 0}, {0, 1, 0});
  PairCounts counts;
  const double f = UnoccludedViewFactor(a, far, PairIntegration{}, counts);
  EXPECT_EQ(counts.one_point, 1u);
  EXPECT_EQ(counts.evaluations, 1u);
  EXPECT_NEAR(f, testing::ParallelRectangles(1, 1, 20), 1e-3 * f);
  EXPECT_EQ(UnoccludedViewFactor(a, behind, PairIntegration{}, counts), 0);
  EXPECT_EQ(counts.culled, 1u);
}

// Between --middle-ratio and --far-ratio a pair takes 2 x 2 Gauss points on i (4 exact
// inner integrals, no refinement), within 2e-4 of the closed form there (1.2e-4 at the
// nearest, below the default --vf-tolerance of 1e-3).
TEST(SurfacePair, MiddlePairsTakeFourPoints) {
  const SurfaceShape a = Square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  for (double c : {4.0, 6.0, 10.0}) {  // gap / diameter of a: 2.3, 3.7, 6.6
    const SurfaceShape b = Square({0, 0, c}, {0, 1, 0}, {1, 0, 0});
    PairCounts counts;
    const double f = UnoccludedViewFactor(a, b, PairIntegration{}, counts);
    EXPECT_EQ(counts.middle, 1u);
    EXPECT_EQ(counts.evaluations, 4u);
    const double exact = testing::ParallelRectangles(1, 1, c);
    EXPECT_NEAR(f, exact, 2e-4 * exact) << "c = " << c;
  }
}

TEST(ShaftCull, OnlyGeometryInTheShaftIsTraced) {
  const SurfaceShape a = Square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});      // faces +z
  const SurfaceShape b = Square({0, 0, 2}, {0, 1, 0}, {1, 0, 0});      // faces -z
  const SurfaceShape middle = Square({0.25, 0.25, 1}, {0.5, 0, 0}, {0, 0.5, 0});
  const SurfaceShape aside = Square({3, 0, 1}, {0.5, 0, 0}, {0, 0.5, 0});
  EXPECT_TRUE(ShaftMayHold(a, b, middle));
  EXPECT_FALSE(ShaftMayHold(a, b, aside));
  EXPECT_TRUE(SegmentHitsSurface({0.5, 0.5, 0}, {0.5, 0.5, 2}, middle));
  EXPECT_FALSE(SegmentHitsSurface({0.1, 0.1, 0}, {0.1, 0.1, 2}, middle));
  const auto crosses = [](const SurfaceShape& k) {
    return [&k](const Vec3& p, const Vec3& q) { return SegmentHitsSurface(p, q, k); };
  };
  // Near (distance 2 for a diameter of 1.4): 4 x 4 points a side. The middle square hides
  // the middle of the view only; a square covering the shaft hides all of it.
  uint64_t segments = 0;
  const double partly = VisibleFraction(a, b, crosses(middle), segments);
  EXPECT_EQ(segments, 256u);
  EXPECT_GT(partly, 0.1);
  EXPECT_LT(partly, 0.9);
  const SurfaceShape cover = Square({-1, -1, 1}, {3, 0, 0}, {0, 3, 0});
  EXPECT_EQ(VisibleFraction(a, b, crosses(cover), segments), 0.0);
  // Far (distance 20): one point a side, the centroids, and the middle square hides it.
  const SurfaceShape far = Square({0, 0, 20}, {0, 1, 0}, {1, 0, 0});
  const SurfaceShape middle_far = Square({0.25, 0.25, 10}, {0.5, 0, 0}, {0, 0.5, 0});
  segments = 0;
  EXPECT_EQ(VisibleFraction(a, far, crosses(middle_far), segments), 0.0);
  EXPECT_EQ(segments, 1u);
  // The one-segment shortcut gives the same answers for the far pair, tests nothing for the
  // near one.
  EXPECT_EQ(OneSegmentVisibleFraction(a, far, crosses(middle_far), segments), 0.0);
  EXPECT_EQ(OneSegmentVisibleFraction(a, far, crosses(aside), segments), 1.0);
  EXPECT_EQ(segments, 3u);
  EXPECT_FALSE(OneSegmentVisibleFraction(a, b, crosses(middle), segments).has_value());
  EXPECT_EQ(segments, 3u);
  const SurfaceShape far_triangle = MakeSurfaceShape({{0, 0, 20}, {0, 1, 20}, {1, 0, 20}});
  const SurfaceShape beside = Square({0.3, 0.3, 10}, {0.1, 0, 0}, {0, 0.1, 0});
  for (const SurfaceShape* k : {&middle_far, &beside}) {
    uint64_t one = 0, all = 0;
    EXPECT_EQ(OneSegmentVisibleFraction(a, far_triangle, crosses(*k), one),
              VisibleFraction(a, far_triangle, crosses(*k), all));
    EXPECT_EQ(one, all);
  }
}

// Two squares crossing through their common centroid (a fuzzer's find: the points-a-side ratio
// diameter / distance is unbounded there): the nearest kind of pair, 4 x 4 points a side on
// the halves in front of each other, 256 segments, nothing hidden.
TEST(ShaftCull, CrossingSurfacesWithOneCentroidTakeTheMostPoints) {
  const SurfaceShape a = Square({-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0});  // faces +z
  const SurfaceShape b = Square({0, -0.5, -0.5}, {0, 1, 0}, {0, 0, 1});  // faces +x
  ASSERT_EQ(Length(a.centroid - b.centroid), 0.0);
  uint64_t segments = 0;
  EXPECT_EQ(VisibleFraction(a, b, [](const Vec3&, const Vec3&) { return false; }, segments), 1.0);
  EXPECT_EQ(segments, 256u);
}

// The unit cube room, n x n squares per wall facing in.
std::vector<SurfaceShape> CubeRoom(int n) {
  std::vector<SurfaceShape> shapes;
  const Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  struct Wall { Vec3 origin, u, v; };  // u x v points into the room
  for (const Wall& w : {Wall{{0, 0, 0}, x, y}, Wall{{0, 0, 1}, y, x}, Wall{{0, 0, 0}, z, x},
                        Wall{{0, 1, 0}, x, z}, Wall{{0, 0, 0}, y, z}, Wall{{1, 0, 0}, z, y}}) {
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        shapes.push_back(Square(w.origin + w.u * (a / double(n)) + w.v * (b / double(n)),
                                w.u / n, w.v / n));
      }
    }
  }
  return shapes;
}

std::vector<std::vector<double>> Rows(const std::vector<SurfaceShape>& shapes,
                                      const SurfaceRowsOptions& options, SurfaceRowsStats& stats) {
  return testing::CollectSurfaceRows(shapes, options, stats);
}

// A closed cube room of 3 x 3 squares per wall: every row sums to 1 (closure), A_i F_ij =
// A_j F_ji (reciprocity), and with nothing inside no pair is traced. Computed row by row
// (a memory limit below the triangle) so that reciprocity is a property of the integration.
TEST(SurfaceRows, ClosedRoomRowsCloseAndAreReciprocal) {
  const std::vector<SurfaceShape> shapes = CubeRoom(3);
  SurfaceRowsOptions options;
  options.integration.tolerance = 1e-5;
  options.memory_limit = 1;
  SurfaceRowsStats stats;
  const std::vector<std::vector<double>> f = Rows(shapes, options, stats);
  EXPECT_FALSE(stats.reciprocal);
  EXPECT_EQ(stats.blockers, 0u);
  EXPECT_EQ(stats.traced_pairs, 0u);
  EXPECT_EQ(stats.segments, 0u);
  for (size_t i = 0; i < f.size(); ++i) {
    double sum = 0;
    for (size_t j = 0; j < f.size(); ++j) {
      sum += f[i][j];
      EXPECT_NEAR(f[i][j] * shapes[i].area, f[j][i] * shapes[j].area, 2e-4 * f[i][j] + 1e-9);
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << "row " << i;
  }
}

// With a box floating in the room (blockers, traced pairs): integrating each pair once and
// taking the other factor by reciprocity gives exactly reciprocal rows, within the
// integration tolerance of the rows computed one by one, traced pairs included.
TEST(SurfaceRows, ReciprocalRowsMatchRowByRow) {
  std::vector<SurfaceShape> shapes = CubeRoom(3);
  const double lo = 0.35, s = 0.3;
  const Vec3 x{s, 0, 0}, y{0, s, 0}, z{0, 0, s}, o{lo, lo, lo}, t = o + x + y + z;
  for (const auto& [origin, u, v] : {std::array{o, y, x}, std::array{o, x, z}, std::array{o, z, y},
                                     std::array{t, -x, -y}, std::array{t, -z, -x},
                                     std::array{t, -y, -z}}) {
    shapes.push_back(Square(origin, u, v));  // faces out of the box
  }
  SurfaceRowsOptions options;
  SurfaceRowsStats once, by_rows;
  const std::vector<std::vector<double>> f = Rows(shapes, options, once);
  options.memory_limit = 1;
  const std::vector<std::vector<double>> g = Rows(shapes, options, by_rows);
  EXPECT_TRUE(once.reciprocal);
  EXPECT_FALSE(by_rows.reciprocal);
  EXPECT_EQ(once.blockers, 6u);
  EXPECT_GT(once.traced_pairs, 50u);
  EXPECT_LT(once.traced_pairs, by_rows.traced_pairs);
  for (size_t i = 0; i < f.size(); ++i) {
    for (size_t j = 0; j < f.size(); ++j) {
      EXPECT_NEAR(f[i][j] * shapes[i].area, f[j][i] * shapes[j].area, 1e-14);
      EXPECT_NEAR(f[i][j], g[i][j], 5e-3 * g[i][j] + 1e-7) << i << " " << j;
    }
  }
}

// Rows do not depend on the thread count, more threads than cores included (their per-thread
// statistics were sized by the cores: --threads 8 on two cores wrote past their end).
TEST(SurfaceRows, MoreThreadsThanCoresGiveTheSameRows) {
  std::vector<SurfaceShape> shapes = CubeRoom(2);
  shapes.push_back(Square({0.4, 0.4, 0.5}, {0.2, 0, 0}, {0, 0.2, 0}));  // a blocker
  for (const size_t memory_limit : {size_t{0}, size_t{1}}) {  // reciprocal, then row by row
    SurfaceRowsOptions options;
    options.memory_limit = memory_limit;
    options.threads = 1;
    SurfaceRowsStats one, many;
    const std::vector<std::vector<double>> f = Rows(shapes, options, one);
    options.threads = 4 * DefaultThreadCount() + 1;
    const std::vector<std::vector<double>> g = Rows(shapes, options, many);
    EXPECT_EQ(f, g);
    EXPECT_EQ(one.traced_pairs, many.traced_pairs);
    EXPECT_GT(one.traced_pairs, 0u);
  }
}

// The memory budget: --memory-limit when given (a hard bound: a triangle one byte over it is
// not held), else a quarter of physical memory; the 15,006-surface grid room's triangle
// (about 859 MiB) fits the default of any machine with 4 GB or more.
TEST(SurfaceRows, TheDefaultBudgetIsAQuarterOfPhysicalMemory) {
  EXPECT_EQ(TriangleBytes(4), 6 * sizeof(double));
  EXPECT_EQ(TriangleBytes(15006), uint64_t{15006} * 15005 / 2 * 8);
  EXPECT_EQ(SurfaceRowsBudget(12345), 12345u);
  const uint64_t physical = PhysicalMemoryBytes();
  ASSERT_GT(physical, uint64_t{1} << 30);
  EXPECT_NEAR(static_cast<double>(SurfaceRowsBudget(0)), 0.25 * static_cast<double>(physical), 1.0);
  const std::vector<SurfaceShape> shapes = CubeRoom(2);  // 24 surfaces: 276 pairs
  SurfaceRowsOptions options;
  SurfaceRowsStats fits, over;
  options.memory_limit = TriangleBytes(24);
  Rows(shapes, options, fits);
  options.memory_limit = TriangleBytes(24) - 1;
  Rows(shapes, options, over);
  EXPECT_TRUE(fits.reciprocal);
  EXPECT_FALSE(over.reciprocal);
  EXPECT_EQ(fits.triangle, TriangleBytes(24));
  EXPECT_EQ(over.budget, TriangleBytes(24) - 1);
  EXPECT_EQ(fits.pairs.culled + fits.pairs.one_point + fits.pairs.middle + fits.pairs.adaptive, 276u);
  EXPECT_EQ(over.pairs.culled + over.pairs.one_point + over.pairs.middle + over.pairs.adaptive,
            2 * 276u);
}

}  // namespace
}  // namespace radflux
