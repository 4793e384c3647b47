#include "solver/formfactor/polygon_form_factor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace radflux {

size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, std::span<const double> distance,
                              std::span<Vec3> out) {
  size_t count = 0;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const size_t next = (k + 1) % polygon.size();
    const Vec3& a = polygon[k];
    const Vec3& b = polygon[next];
    const double da = distance[k], db = distance[next];
    if (da >= 0) out[count++] = a;
    if ((da >= 0) != (db >= 0)) out[count++] = a + (b - a) * (da / (da - db));
  }
  return count;
}

size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin, const Vec3& n,
                              std::span<Vec3> out) {
  std::array<double, kMaxClipVertices> distance;
  for (size_t k = 0; k < polygon.size(); ++k) distance[k] = Dot(polygon[k] - origin, n);
  return ClipPolygonToHalfSpace(polygon, std::span<const double>(distance.data(), polygon.size()),
                                out);
}

std::vector<Vec3> ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin,
                                         const Vec3& n) {
  std::vector<double> distance;
  for (const Vec3& p : polygon) distance.push_back(Dot(p - origin, n));
  std::vector<Vec3> out(2 * polygon.size());
  out.resize(ClipPolygonToHalfSpace(polygon, distance, out));
  return out;
}

double UnclippedPointToPolygonFormFactor(const Vec3& x, const Vec3& n,
                                         std::span<const Vec3> polygon) {
  // Each vertex relative to x once, and no index wrap-around in the loop.
  const Vec3 first = polygon[0] - x;
  Vec3 a = first;
  double sum = 0;
  for (size_t k = 1; k < polygon.size(); ++k) {
    const Vec3 b = polygon[k] - x;
    sum += ContourEdgeTerm(a, b, n);
    a = b;
  }
  sum += ContourEdgeTerm(a, first, n);
  return FormFactorFromContourSum(sum);
}

double PointToPolygonFormFactor(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon) {
  bool all_front = true, any_front = false;
  for (const Vec3& p : polygon) {
    const double d = Dot(p - x, n);
    all_front = all_front && d >= 0;
    any_front = any_front || d > 0;
  }
  if (!any_front) return 0;
  if (all_front) return UnclippedPointToPolygonFormFactor(x, n, polygon);
  const std::vector<Vec3> clipped = ClipPolygonToHalfSpace(polygon, x, n);
  return clipped.size() < 3 ? 0 : UnclippedPointToPolygonFormFactor(x, n, clipped);
}

}  // namespace radflux
