// The parameters of a point on a quad under its bilinear map, as subdivide.h and the
// renderer place points on quads.
#pragma once

#include <array>
#include <utility>

#include "solver/core/vec3.h"

namespace radflux {

// Parameters (s, t) in [0, 1]^2 of `point` (projected on the plane of quad v, unit normal
// `normal`) under the bilinear map v0 + s (v1 - v0) + t (v3 - v0) + s t (v0 - v1 + v2 - v3):
// the root in [0, 1] (or the nearest to it) of the quadratic in s that the map's 2D cross
// product gives. A point beyond the quad reads the nearest edge's parameter (0 or 1).
std::pair<double, double> InverseBilinear(const std::array<Vec3, 4>& v, const Vec3& normal,
                                          const Vec3& point);

}  // namespace radflux
