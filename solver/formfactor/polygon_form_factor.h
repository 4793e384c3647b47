// Exact differential-area-to-polygon form factor (Lambert's contour integral), with
// the polygon clipped to the half-space the differential area faces.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "solver/core/vec3.h"

namespace radflux {

// F from a differential area at x with unit normal n to the planar polygon `polygon`
// (any winding), unoccluded. Parts of the polygon behind x's tangent plane are clipped
// away first. Result in [0, 1].
double PointToPolygonFormFactor(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon);

// The part of `polygon` with Dot(p - origin, n) >= 0 (Sutherland-Hodgman against one plane).
std::vector<Vec3> ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin,
                                         const Vec3& n);
// The same into `out` (room for polygon.size() + 1 vertices) for a polygon of at most
// kMaxClipVertices vertices; returns the vertex count. Allocates nothing.
inline constexpr size_t kMaxClipVertices = 8;
size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin, const Vec3& n,
                              std::span<Vec3> out);
// The same for any polygon, given each vertex's distance[k] = Dot(polygon[k] - origin, n);
// returns the vertex count. Allocates nothing: the form-factor builders clip once per patch
// pair, with the distances they already have.
size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, std::span<const double> distance,
                              std::span<Vec3> out);

// Lambert's contour sum for a polygon already in front of x: no clipping.
double UnclippedPointToPolygonFormFactor(const Vec3& x, const Vec3& n,
                                         std::span<const Vec3> polygon);

// One edge's term of Lambert's contour sum: gamma n.(a x b) / |a x b| for the edge from
// x + a to x + b, gamma the angle it subtends at x; 0 when the edge points at x. The
// reversed edge (b, a) gives exactly the negated term (bit for bit), so patches sharing
// an edge can share its term.
inline double ContourEdgeTerm(const Vec3& a, const Vec3& b, const Vec3& n) {
  const Vec3 c = Cross(a, b);
  const double cross_len = Length(c);
  if (cross_len == 0) return 0;
  return std::atan2(cross_len, Dot(a, b)) * Dot(n, c) / cross_len;
}

// The form factor, in [0, 1], of a polygon whose contour terms sum (in edge order) to `sum`.
inline double FormFactorFromContourSum(double sum) {
  return std::clamp(std::abs(sum) / (2 * std::numbers::pi), 0.0, 1.0);
}

}  // namespace radflux
