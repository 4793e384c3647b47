// Face grouping: the unknowns follow a target count, not the modeller's tessellation. When a
// scene has at least as many faces as the N unknowns asked for, every face as one patch would
// give walls a few huge patches and fine-tessellated furniture most of the unknowns. Instead,
// with a* = (total face area) / N:
//  - faces are split to an edge length of kSplitEdge * sqrt(a*) (large faces become patches
//    of about a*; emitters keep subdivide.h's cap), and every emitting patch is an unknown
//    of its own (light sampling needs emitters as single polygons);
//  - the other patches are put, per (object, material, two-sidedness), in a binary tree by top-down
//    median splits (a BVH build): a node whose normals spread beyond kMaxConeDegrees of their
//    area-weighted mean is split along the normal component that varies most (so that groups
//    are flat, and a group's rays seldom hit the group itself), any other node along its
//    centroids' longest axis;
//  - the unknowns are a cut of these trees with N nodes in all (fewer only when the trees
//    run out of nodes): starting from the roots, the node of largest
//        max(area, (diagonal / kMaxExtent)^2) * (1 + kConeWeight (1 - min cos))
//    is replaced by its children (min cos: the smallest cosine between a member's normal and
//    the node's area-weighted mean normal). Large, spread-out or bent groups split first.
// Grouping is exact Galerkin with one constant per group (rows average members' rows by area;
// a hit on a member counts for the group), so its only error is that of a constant B over a
// group of size ~a*, as for one patch of that size; rays from a group that hit the same group
// (F_CC, non-zero only for a non-flat group) are not in the rows: light the group would
// reflect back onto itself leaves the system (the report counts it as escaped).
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "solver/mesh/patch_clusters.h"
#include "solver/mesh/subdivide.h"

namespace radflux {

inline constexpr double kSplitEdge = 1.5;
inline constexpr double kMaxExtent = 2.0;
inline constexpr double kMaxConeDegrees = 30.0;
inline constexpr double kConeWeight = 2.0;

// Whether SubdivideAndGroup groups faces for these options: group_faces, and a target patch
// count (not --max-edge) no larger than the scene's face count.
bool GroupsFaces(const Scene& scene, const MeshOptions& options);

struct GroupedMesh {
  PatchMesh mesh;          // the patches (what outputs draw)
  PatchClusters clusters;  // the unknowns; empty when the faces were not grouped
};

// The scene's patches and unknowns: with GroupsFaces, split and grouped as above to about
// options.target_patches unknowns; otherwise SubdivideScene's mesh, one unknown per patch.
absl::StatusOr<GroupedMesh> SubdivideAndGroup(const Scene& scene, const MeshOptions& options);

// Groups the patches of `mesh` (of `scene`) into `unknowns` unknowns (or more: at least one
// per emitting patch and per (object, material, two-sidedness); or fewer: when every group is
// one patch) by the rule above. A group never spans two objects, so per-object means stay
// each object's own.
PatchClusters GroupPatches(const Scene& scene, const PatchMesh& mesh, int64_t unknowns);

}  // namespace radflux
