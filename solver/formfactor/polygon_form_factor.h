// Exact differential-area-to-polygon form factor (Lambert's contour integral), with
// the polygon clipped to the half-space the differential area faces.
#pragma once

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
// The same into `out` (room for polygon.size() + 1 vertices); returns the vertex count.
// Allocates nothing: the form-factor builders clip once per patch pair.
size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin, const Vec3& n,
                              std::span<Vec3> out);

// Lambert's contour sum for a polygon already in front of x: no clipping.
double UnclippedPointToPolygonFormFactor(const Vec3& x, const Vec3& n,
                                         std::span<const Vec3> polygon);

}  // namespace radflux
