// The unoccluded view factor between two planar convex surfaces, integrated as the pair needs
// (issue 23, after View3D's idea): the inner integral over j is always exact (Lambert's
// contour sum, PointToPolygonFormFactor); the outer integral over i is
//   - one point, i's centroid, when the pair is far (distance / i's diameter >= far_ratio),
//   - 2 x 2 Gauss points per cell of i between middle_ratio and far_ratio,
//   - adaptive otherwise: i (a quadrilateral through its bilinear map, a triangle through
//     Duffy's collapsed square, other polygons as a fan of triangles) is integrated with 2 x 2
//     and 3 x 3 Gauss points; where they disagree by more than `tolerance` (relative) the
//     cell is split in four at its edge midpoints, recursively. Smooth (separated) pairs stop
//     at once; pairs sharing an edge (a log singularity along it) refine near the edge.
// Parts of i behind j's plane contribute nothing (i is clipped to j's front first). "Behind"
// and "in front" leave out a band around each plane (CoplanarBand): a face sees nothing in
// its own plane, however its vertices were rounded (coincident twins, coplanar overlaps).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/core/vec3.h"

namespace radflux {

// One surface as the view-factor rows read it.
struct SurfaceShape {
  std::vector<Vec3> polygon;  // counter-clockwise seen from the front, convex, planar
  Vec3 normal;                // unit, towards the front
  Vec3 centroid;              // area-weighted
  double area = 0;            // m^2 (scene units^2)
  double diameter = 0;        // the longest distance between two vertices
  double flatness = 0;        // scene units: the largest distance of a vertex from the plane
                              // (normal through centroid); 0 for a triangle, up to the import
                              // rules' planarity tolerance for a rounded quadrilateral
  Vec3 lo, hi;                // bounding box
  float opacity = 1;          // Material::opacity: as a blocker, a segment crosses it with
                              // probability 1 - opacity (BlockerBvh::SegmentBlocked)
};

// The shape of a convex polygon (at least 3 vertices, non-degenerate).
SurfaceShape MakeSurfaceShape(std::vector<Vec3> polygon);

struct PairIntegration {
  double far_ratio = 8;      // one point beyond this distance / diameter of i
  double middle_ratio = 2;   // 2 x 2 Gauss points per cell of i beyond this one
  double tolerance = 1e-3;   // adaptive: relative disagreement accepted per triangle
  int max_depth = 6;         // adaptive: at most this many splits of a cell of i
};

// What the pair integrations did, summed over the pairs of a run.
struct PairCounts {
  uint64_t culled = 0;       // j behind or in i's plane, or i in or behind j's: no work
  uint64_t one_point = 0;    // far pairs
  uint64_t middle = 0;       // pairs between middle_ratio and far_ratio
  uint64_t adaptive = 0;     // near pairs
  uint64_t evaluations = 0;  // exact point-to-polygon integrals
  void Merge(const PairCounts& o);
};

// The distance (scene units) within which a vertex of b counts as on a's plane: twice both
// faces' flatness plus kCoplanarRelative of their diameters. A face and its back-face twin,
// or two coplanar faces whose vertices were rounded, lie within it of each other's plane.
inline constexpr double kCoplanarRelative = 1e-6;
double CoplanarBand(const SurfaceShape& a, const SurfaceShape& b);

// Whether some vertex of b lies in front of (behind) a's plane by more than
// CoplanarBand(a, b).
bool PartlyInFront(const SurfaceShape& a, const SurfaceShape& b);
bool PartlyBehind(const SurfaceShape& a, const SurfaceShape& b);

// Whether j has a part in front of i's plane and i a part in front of j's, beyond the
// coplanar band (else F_ij = 0: back to back, behind, or in one plane).
bool CanSeeEachOther(const SurfaceShape& i, const SurfaceShape& j);

// F_ij without occlusion, in [0, 1].
double UnoccludedViewFactor(const SurfaceShape& i, const SurfaceShape& j,
                            const PairIntegration& options, PairCounts& counts);

}  // namespace radflux
