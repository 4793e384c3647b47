// Convexity and joining of the polygons contact meshing cuts along (contact_footprints.h):
// convex polygons clip as they are, others as triangles, and the triangles of a modeller's
// tessellated rectangle are better cut along as the rectangle.
#pragma once

#include <vector>

#include "solver/core/vec3.h"

namespace radflux {

// Whether polygon p turns left about `normal` at every corner: the turn's cross product along
// `normal` is at least -tol times the two edges' lengths (tol = 0: no right turn at all).
bool IsConvexPolygon(const std::vector<Vec3>& p, const Vec3& normal, double tol = 0);

// `polygons` (each counter-clockwise about `normal`) with every two that share an edge,
// the opposite ways round within tol, joined into one while their union is convex, until no
// two do. Polygons that share no edge are returned as they are.
std::vector<std::vector<Vec3>> JoinedConvexPolygons(std::vector<std::vector<Vec3>> polygons,
                                                    const Vec3& normal, double tol);

}  // namespace radflux
