// Ear clipping and the quad split: triangles that tile the polygon (their areas sum to the
// polygon's, each facing the polygon's way) for convex, non-convex and collinear cases.
#include "solver/scene/polygon_triangulation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/scene/scene.h"

namespace radflux {
namespace {

// Sum of the triangles' signed areas about +z, and the smallest of them.
std::pair<double, double> Areas(const std::vector<Vec3>& p, const std::vector<TriangleCorners>& t) {
  double sum = 0, smallest = INFINITY;
  for (const TriangleCorners& c : t) {
    const double a = Cross(p[c[1]] - p[c[0]], p[c[2]] - p[c[0]]).z / 2;
    sum += a;
    smallest = std::min(smallest, a);
  }
  return {sum, smallest};
}

TEST(PolygonTriangulation, CombTilesItsAreaWithPositiveTriangles) {
  // A comb: 4 teeth of width 1 and height 2 on a 7 x 1 base; area 7 + 4 * 2 = 15.
  std::vector<Vec3> comb = {{0, 0, 0}, {7, 0, 0}, {7, 3, 0}, {6, 3, 0}, {6, 1, 0}, {5, 1, 0},
                            {5, 3, 0}, {4, 3, 0}, {4, 1, 0}, {3, 1, 0}, {3, 3, 0}, {2, 3, 0},
                            {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  const std::vector<TriangleCorners> t = TriangulatePolygon(comb, {0, 0, 1});
  EXPECT_EQ(t.size(), comb.size() - 2);
  const auto [sum, smallest] = Areas(comb, t);
  EXPECT_NEAR(sum, 15.0, 1e-12);
  EXPECT_GT(smallest, 0);
}

TEST(PolygonTriangulation, CollinearVerticesMakeNoZeroAreaTriangle) {
  // A unit square with an extra vertex in the middle of each edge.
  std::vector<Vec3> square = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 0.5, 0},
                              {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}, {0, 0.5, 0}};
  const std::vector<TriangleCorners> t = TriangulatePolygon(square, {0, 0, 1});
  const auto [sum, smallest] = Areas(square, t);
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_GT(smallest, 1e-6);
}

TEST(PolygonTriangulation, ClockwiseAboutTheNormalIsStillCovered) {
  // Seen from -z the L shape is counter-clockwise: triangulated about (0, 0, -1).
  std::vector<Vec3> l = {{0, 0, 0}, {0, 2, 0}, {1, 2, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}};
  const std::vector<TriangleCorners> t = TriangulatePolygon(l, {0, 0, -1});
  const auto [sum, smallest] = Areas(l, t);
  EXPECT_NEAR(sum, -3.0, 1e-12);  // clockwise about +z, as the polygon
  EXPECT_LT(smallest, 0);
  EXPECT_EQ(t.size(), 4u);
}

TEST(PolygonTriangulation, QuadSplitTakesTheShorterDiagonal) {
  const std::vector<Vec3> kite = {{0, 0, 0}, {1, -0.2, 0}, {3, 0, 0}, {1, 0.2, 0}};  // 1-3 short
  EXPECT_EQ(SplitQuad(kite), (std::vector<TriangleCorners>{{0, 1, 3}, {1, 2, 3}}));
  const std::vector<Vec3> other = {{0, 0, 0}, {1, -2, 0}, {2, 0, 0}, {1, 2, 0}};  // 0-2 short
  EXPECT_EQ(SplitQuad(other), (std::vector<TriangleCorners>{{0, 1, 2}, {0, 2, 3}}));
}

}  // namespace
}  // namespace radflux
