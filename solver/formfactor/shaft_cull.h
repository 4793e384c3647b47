// Which surfaces can hide part of j from i (issue 23: "visibility rays only for pairs whose
// shaft holds geometry"). Three filters, each exact in what it rules out:
//   1. a surface with all the scene in front of or on its plane (a room's walls, the ground
//      of a city) can block nothing: a segment between two points in its closed front
//      half-space only touches its plane where both ends lie in it (PotentialBlockers);
//   2. a blocker of the pair lies partly in front of i's plane and of j's (RowBlockers, then
//      per pair);
//   3. a separating axis (the three coordinate axes, the normals of i, j and k, and the
//      shaft direction crossed with k's edges and the axes) between the convex hull of i and
//      j and the polygon k proves k misses the shaft (ShaftMayHold).
// What survives may or may not block: its pairs are traced (shaft_visibility.h).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/formfactor/surface_pair_integrator.h"

namespace radflux {

// The surfaces of `shapes` that some other geometry lies strictly behind (filter 1),
// ascending.
std::vector<uint32_t> PotentialBlockers(const std::vector<SurfaceShape>& shapes);

// Those of `blockers` with a vertex strictly in front of i's plane, other than i (filter 2).
std::vector<uint32_t> RowBlockers(const std::vector<SurfaceShape>& shapes,
                                  const std::vector<uint32_t>& blockers, uint32_t i);

// False when k provably does not meet the convex hull of i and j (filters 2 and 3 for j).
bool ShaftMayHold(const SurfaceShape& i, const SurfaceShape& j, const SurfaceShape& k);

}  // namespace radflux
