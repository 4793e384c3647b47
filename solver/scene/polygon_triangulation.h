// Triangles for polygons the solver cannot take whole: ear clipping in a polygon's plane
// (non-convex faces) and the shorter-diagonal split of a quad (non-planar faces). Both
// keep the polygon's winding, so every triangle faces the way the polygon did.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/vec3.h"

namespace radflux {

using TriangleCorners = std::array<uint32_t, 3>;  // indices into the polygon's vertex list

// Triangles covering the simple polygon `polygon` (>= 3 vertices), found by ear clipping
// in the plane with unit normal `normal` (the polygon's Newell normal): n - 2 triangles at
// most; a collinear vertex is clipped without a triangle (no zero-area triangle is made).
// A polygon that is not simple (self-touching, mildly non-planar) still gets triangles
// that cover it: when no ear is free of other vertices the most convex corner is clipped.
std::vector<TriangleCorners> TriangulatePolygon(const std::vector<Vec3>& polygon,
                                                const Vec3& normal);

// The two triangles of quad (p0, p1, p2, p3), split along its shorter diagonal.
std::vector<TriangleCorners> SplitQuad(const std::vector<Vec3>& quad);

}  // namespace radflux
