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
// The same into `out` for a polygon of at most kMaxClipVertices vertices; returns the vertex
// count. `out` needs room for 2 * polygon.size() vertices: a convex polygon gives at most
// polygon.size() + 1, but a sliver lying along the plane can change side on every edge
// when rounded (seen on RenderPark's office2). Allocates nothing.
inline constexpr size_t kMaxClipVertices = 8;
size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin, const Vec3& n,
                              std::span<Vec3> out);
// The same for any polygon, given each vertex's distance[k] = Dot(polygon[k] - origin, n);
// returns the vertex count (at most 2 * polygon.size(), the room `out` needs). Allocates nothing: the form-factor builders clip once per patch
// pair, with the distances they already have.
size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, std::span<const double> distance,
                              std::span<Vec3> out);

// Lambert's contour sum for a polygon already in front of x: no clipping. The sum of
// ContourEdgeTerm over the edges in order, bit for bit (two edges at a time on the
// small-angle path).
double UnclippedPointToPolygonFormFactor(const Vec3& x, const Vec3& n,
                                         std::span<const Vec3> polygon);

// atan(t) / t for u = t^2 < kSmallAngleTan2: its Taylor series 1 - u/3 + u^2/5 - ... to
// the u^12 term (the first omitted one is below 1e-17), in Estrin's order (short
// dependency chains).
inline constexpr double kSmallAngleTan2 = 1.0 / 16;  // tan^2 of ~14 degrees
// T is double, or a GCC vector of doubles (the same operations lane by lane).
template <typename T>
inline T AtanOverTOfSquare(T u) {
  // Coefficient k is (-1)^k / (2k + 1), rounded once at compile time (no division here).
  constexpr double c[13] = {1.0,       -1.0 / 3,  1.0 / 5,   -1.0 / 7, 1.0 / 9,
                            -1.0 / 11, 1.0 / 13,  -1.0 / 15, 1.0 / 17, -1.0 / 19,
                            1.0 / 21,  -1.0 / 23, 1.0 / 25};
  const T u2 = u * u, u4 = u2 * u2, u8 = u4 * u4;
  return ((c[0] + c[1] * u) + u2 * (c[2] + c[3] * u)) +
         u4 * ((c[4] + c[5] * u) + u2 * (c[6] + c[7] * u)) +
         u8 * (((c[8] + c[9] * u) + u2 * (c[10] + c[11] * u)) + u4 * c[12]);
}

// One edge's term of Lambert's contour sum: gamma n.(a x b) / |a x b| for the edge from
// x + a to x + b, gamma the angle it subtends at x; 0 when the edge points at x. An edge
// seen under less than ~14 degrees (most of a row's) takes gamma / |a x b| =
// atan(t) / (t a.b), t = tan gamma, from its series: no square root, no atan2, within a
// few ulp of the atan2 form (tested: below 8). The reversed edge (b, a) gives exactly the
// negated term (bit for bit), so patches sharing an edge can share its term.
inline double ContourEdgeTerm(const Vec3& a, const Vec3& b, const Vec3& n) {
  const Vec3 c = Cross(a, b);
  const double d = Dot(a, b);
  const double c2 = Dot(c, c);
  if (d > 0 && c2 < kSmallAngleTan2 * (d * d)) {
    const double inv_d = 1 / d;
    return AtanOverTOfSquare(c2 * (inv_d * inv_d)) * inv_d * Dot(n, c);
  }
  const double cross_len = std::sqrt(c2);
  if (cross_len == 0) return 0;
  return std::atan2(cross_len, d) * Dot(n, c) / cross_len;
}

// The form factor, in [0, 1], of a polygon whose contour terms sum (in edge order) to `sum`.
inline double FormFactorFromContourSum(double sum) {
  return std::clamp(std::abs(sum) / (2 * std::numbers::pi), 0.0, 1.0);
}

}  // namespace radflux
