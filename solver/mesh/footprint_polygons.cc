#include "solver/mesh/footprint_polygons.h"

#include <cstddef>
#include <utility>

namespace radflux {
namespace {

using Polygon = std::vector<Vec3>;

// a and b joined along an edge they share the opposite ways round, when they share one and
// the union is convex; empty otherwise.
Polygon JoinedConvex(const Polygon& a, const Polygon& b, const Vec3& normal, double tol) {
  for (size_t i = 0; i < a.size(); ++i) {
    const Vec3& from = a[i];
    const Vec3& to = a[(i + 1) % a.size()];
    for (size_t j = 0; j < b.size(); ++j) {
      if (Length(b[j] - to) > tol || Length(b[(j + 1) % b.size()] - from) > tol) continue;
      Polygon joined;
      for (size_t k = 1; k <= a.size(); ++k) joined.push_back(a[(i + k) % a.size()]);
      for (size_t k = 2; k < b.size(); ++k) joined.push_back(b[(j + k) % b.size()]);
      return IsConvexPolygon(joined, normal, tol) ? joined : Polygon{};
    }
  }
  return {};
}

}  // namespace

bool IsConvexPolygon(const std::vector<Vec3>& p, const Vec3& normal, double tol) {
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % p.size()];
    const Vec3& c = p[(i + 2) % p.size()];
    if (Dot(Cross(b - a, c - b), normal) < -tol * (Length(b - a) + Length(c - b))) return false;
  }
  return true;
}

std::vector<std::vector<Vec3>> JoinedConvexPolygons(std::vector<std::vector<Vec3>> polygons,
                                                    const Vec3& normal, double tol) {
  for (size_t i = 0; i < polygons.size(); ++i) {
    for (size_t j = i + 1; j < polygons.size(); ++j) {
      Polygon joined = JoinedConvex(polygons[i], polygons[j], normal, tol);
      if (joined.empty()) continue;
      polygons[i] = std::move(joined);
      polygons.erase(polygons.begin() + static_cast<std::ptrdiff_t>(j));
      j = i;  // polygons[i] changed: try every later one again
    }
  }
  return polygons;
}

}  // namespace radflux
