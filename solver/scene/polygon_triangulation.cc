#include "solver/scene/polygon_triangulation.h"

#include <cmath>
#include <algorithm>
#include <cstddef>

namespace radflux {
namespace {

struct Point2D {
  double x = 0, y = 0;
};

double Cross2(const Point2D& o, const Point2D& a, const Point2D& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Whether p lies inside or on triangle (a, b, c) (counter-clockwise).
bool InTriangle(const Point2D& p, const Point2D& a, const Point2D& b, const Point2D& c) {
  return Cross2(a, b, p) >= 0 && Cross2(b, c, p) >= 0 && Cross2(c, a, p) >= 0;
}

// The polygon in 2D coordinates of its plane, counter-clockwise about `normal`.
std::vector<Point2D> Project(const std::vector<Vec3>& polygon, const Vec3& normal) {
  const Frame frame = Frame::FromNormal(normal);
  std::vector<Point2D> points;
  points.reserve(polygon.size());
  for (const Vec3& p : polygon) points.push_back({Dot(p - polygon[0], frame.s), Dot(p - polygon[0], frame.t)});
  return points;
}

}  // namespace

std::vector<TriangleCorners> TriangulatePolygon(const std::vector<Vec3>& polygon,
                                                const Vec3& normal) {
  const std::vector<Point2D> p = Project(polygon, normal);
  double span = 0;
  for (const Point2D& q : p) span = std::max({span, std::abs(q.x), std::abs(q.y)});
  const double flat = 1e-12 * span * span;  // twice the area of a triangle taken as zero
  std::vector<uint32_t> ring(polygon.size());
  for (uint32_t i = 0; i < ring.size(); ++i) ring[i] = i;
  std::vector<TriangleCorners> triangles;
  while (ring.size() >= 3) {
    const size_t n = ring.size();
    size_t chosen = n, most_convex = 0;
    double best = -INFINITY;
    for (size_t i = 0; i < n && chosen == n; ++i) {
      const uint32_t a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
      const double turn = Cross2(p[a], p[b], p[c]);
      if (turn > best) best = turn, most_convex = i;
      if (std::abs(turn) <= flat) {
        chosen = i;  // collinear: clipped without a triangle
        break;
      }
      if (turn < 0) continue;
      bool empty = true;
      for (size_t j = 0; j < n && empty; ++j) {
        const uint32_t q = ring[j];
        if (q == a || q == b || q == c) continue;
        const bool shared = (p[q].x == p[a].x && p[q].y == p[a].y) ||
                            (p[q].x == p[b].x && p[q].y == p[b].y) ||
                            (p[q].x == p[c].x && p[q].y == p[c].y);
        empty = shared || !InTriangle(p[q], p[a], p[b], p[c]);
      }
      if (empty) chosen = i;
    }
    if (chosen == n) chosen = most_convex;
    const uint32_t a = ring[(chosen + n - 1) % n], b = ring[chosen], c = ring[(chosen + 1) % n];
    if (std::abs(Cross2(p[a], p[b], p[c])) > flat) triangles.push_back({a, b, c});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(chosen));
  }
  return triangles;
}

std::vector<TriangleCorners> SplitQuad(const std::vector<Vec3>& quad) {
  if (Length(quad[2] - quad[0]) <= Length(quad[3] - quad[1])) return {{0, 1, 2}, {0, 2, 3}};
  return {{0, 1, 3}, {1, 2, 3}};
}

}  // namespace radflux
