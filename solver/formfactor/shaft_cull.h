// Which surfaces can hide part of j from i (issue 23: "visibility rays only for pairs whose
// shaft holds geometry"). Three filters, each exact in what it rules out:
//   1. a surface with all the scene in front of or on its plane (a room's walls, the ground
//      of a city) can block nothing: a segment between two points in its closed front
//      half-space only touches its plane where both ends lie in it (PotentialBlockers);
//   2. a blocker of the pair lies partly in front of i's plane and of j's (MayBlockPair);
//   3. a separating axis (the three coordinate axes, the normals of i, j and k, and the
//      shaft direction crossed with the axes and with k's edges) between the convex hull of
//      i and j and the polygon k proves k misses the shaft (Shaft).
// What survives may or may not block: its pairs are traced (shaft_visibility.h). A pair finds
// its candidates through a hierarchy over the blockers (blocker_bvh.h), which tests boxes of
// blockers against the same shaft.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/formfactor/surface_pair_integrator.h"

namespace radflux {

// The surfaces of `shapes` that some other geometry lies strictly behind (filter 1, beyond
// the coplanar band: a back-face twin is not "behind"), ascending. A surface with the whole
// scene's bounding box in front of its plane (a room's walls, the ground) is ruled out at
// once; the others are tested against every vertex until one lies behind.
std::vector<uint32_t> PotentialBlockers(const std::vector<SurfaceShape>& shapes);

// Filter 2: whether k has a vertex in front of i's plane and one in front of j's, beyond the
// coplanar band (CoplanarBand). A k lying in i's plane (i's twin, a coplanar neighbour) or
// behind it cannot hide anything i sees; the same for j.
bool MayBlockPair(const SurfaceShape& i, const SurfaceShape& j, const SurfaceShape& k);

// The convex hull of a pair (i, j) as its extents on the separating axes that do not depend
// on a blocker, computed once per pair (the coordinate axes at once, the others when a box
// passes those). Not thread-safe: one per pair and thread.
class Shaft {
 public:
  // The shaft of i and j; `margin` (scene units, >= 0) widens every test so that touching
  // counts as meeting. i and j must outlive it.
  Shaft(const SurfaceShape& i, const SurfaceShape& j, double margin);

  // False when an axis provably separates the box (centre, half extents) from the shaft.
  bool MayMeetBox(const Vec3& center, const Vec3& half) const;

  // False when k provably does not meet the shaft or lies on or behind i's plane or j's
  // (filters 2 and 3); k must be neither i nor j.
  bool MayHold(const SurfaceShape& k) const;

 private:
  static constexpr int kAxes = 8;  // x, y, z, i's normal, j's normal, d x (x, y, z)
  bool Separates(const Vec3& axis, const SurfaceShape& k) const;
  void Complete() const;  // the axes after the coordinate ones, on first need

  const SurfaceShape& i_;
  const SurfaceShape& j_;
  Vec3 d_;  // centroid of i to centroid of j
  mutable Vec3 axis_[kAxes], abs_axis_[kAxes];
  mutable double lo_[kAxes], hi_[kAxes];  // the shaft's extent on each axis, widened
  double margin_;
  mutable bool complete_ = false;
};

// Shaft(i, j, m).MayHold(k) with a margin m relative to the three surfaces' sizes; false
// when k is i or j.
bool ShaftMayHold(const SurfaceShape& i, const SurfaceShape& j, const SurfaceShape& k);

}  // namespace radflux
