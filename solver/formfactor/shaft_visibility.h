// The visible fraction of a surface pair whose shaft may hold blockers (shaft_cull.h):
// segments between midpoint-rule points on i and on j (1 to 4 x 4 a side per cell, more for a
// surface near and large for the pair; on the part of the polygon in front of the other's
// plane when it straddles that plane, so that a pair seeing each other only in part is
// sampled where it does), each tested exactly against the candidate blockers' polygons,
// weighted by the points' areas and the form-factor kernel cos cos / r^2 so that the
// fraction is consistent where visibility varies across the pair. The same points and
// answers whichever of the two is i.
#pragma once

#include <cstdint>
#include <optional>

#include "absl/functional/function_ref.h"

#include "solver/formfactor/surface_pair_integrator.h"

namespace radflux {

// Whether the open segment from a to b crosses the plane through `point` with unit `normal`
// (its ends strictly on either side); the same answer for (b, a). SegmentHitsSurface's first
// test, with its arithmetic: false here means false there.
inline bool SegmentCrossesPlane(const Vec3& a, const Vec3& b, const Vec3& point, const Vec3& normal) {
  const double da = Dot(a - point, normal), db = Dot(b - point, normal);
  return (da > 0) != (db > 0) && da != 0 && db != 0;
}

// Whether the open segment from a to b crosses the convex polygon of k; the same answer
// for (b, a).
bool SegmentHitsSurface(const Vec3& a, const Vec3& b, const SurfaceShape& k);

// blocked(a, b): whether something crosses the open segment from a to b.
using SegmentTest = absl::FunctionRef<bool(const Vec3& a, const Vec3& b)>;

// The kernel-weighted fraction of segments from i to j that are not `blocked`, in [0, 1];
// adds the segments tested to `segments`.
double VisibleFraction(const SurfaceShape& i, const SurfaceShape& j, SegmentTest blocked,
                       uint64_t& segments);

// VisibleFraction(i, j, blocked, segments), 0 or 1, when it takes one point a side on whole
// triangles or quadrilaterals (a pair far for its size: one segment), found without its
// sample arrays; nullopt (nothing tested) when it takes more.
std::optional<double> OneSegmentVisibleFraction(const SurfaceShape& i, const SurfaceShape& j,
                                                SegmentTest blocked, uint64_t& segments);

}  // namespace radflux
