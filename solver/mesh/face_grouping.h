// Face grouping: the unknowns follow a target count, not the modeller's tessellation. When a
// scene has at least as many faces as the N unknowns asked for, every face as one patch would
// give walls a few huge patches and fine-tessellated furniture most of the unknowns. Instead,
// with a* = (total face area) / N:
//  - faces are split to an edge length of kSplitEdge * sqrt(a*) (large faces become patches
//    of about a*; emitters keep subdivide.h's cap), quads close to an emitter against their
//    size further into strips across its light (formfactor/near_field_cuts.h: a housing's inside
//    along its tube), and every emitting patch is an unknown of its own (light sampling needs
//    emitters as single polygons), as is every hidden patch (in a slot under an emitter: its light
//    is not its neighbours'); faces of area a* or more are cut along their contacts and lose the
//    area under solids and covers hung against them (contact_footprints.h; with follow_contacts): a
//    wall's patch that straddled a board's outline averaged the dark behind it into the lit strip
//    beside it;
//  - every patch is probed for the emitters' direct light (direct_lit.h: a light sample per
//    patch through its own Embree scene, kept for the job's rows): a patch whose reflected
//    direct light makes it a light source (kBright: a lamp housing's inside) is an unknown of
//    its own, so that the rows light-sample it as a bright reflector (bright_reflectors.h);
//  - the other patches are put, per (object, material, two-sidedness, side, lit or not), in a
//    binary tree by top-down median splits (a BVH build); a face never shares an unknown with
//    a back-face twin (two_sided.h: at the same centroids, the splits never parted them, and a
//    ceiling grouped with its outward twins sent half its light out of the room: RenderPark's
//    classroom lost 25% of its emitted power at --patches 1000, 6% at 2000, its ceiling -45%
//    and -9%); a lit patch never shares an unknown with an unlit one (a housing's inside, 2 cm from
//    its tube, with its outer side and the cavity between its shells: grouped, RenderPark's
//    classroom's ceiling 2 cm above the housings gathered the insides' light and read +95%); a node
//    whose normals spread beyond kMaxConeDegrees of their area-weighted mean and whose centroids
//    span at most kMaxExtent sqrt(a*) is split along the normal component that varies most (so that
//    groups are flat, and a group's rays seldom hit the group itself), any other node along its
//    centroids' longest axis (a bent node as large as a room, all its chairs, is split in space
//    first: split by normals, its children would span the room as it does, and the cut would spend
//    the unknowns on them before the ceiling got any);
//  - the unknowns are a cut of these trees with N nodes in all (fewer only when the trees
//    run out of nodes): starting from the roots, the node of largest
//        max(area, (diagonal / kMaxExtent)^2) * (1 + kConeWeight (1 - min cos))
//    is replaced by its children (min cos: the smallest cosine between a member's normal and
//    the node's area-weighted mean normal). Large, spread-out or bent groups split first.
// Grouping is exact Galerkin with one constant per group (rows average members' rows by area;
// a hit on a member counts for the group), so its only error is that of a constant B over a
// group of size ~a*, as for one patch of that size; rays from a group that hit the same group
// count for it too (F_CC, Galerkin's diagonal, non-zero only for a non-flat group: a lamp
// housing's inside, which reflects much of its light onto itself; every solver and the energy
// balance take a diagonal). What grouping still loses is resolution within the group (a tube
// 2 cm under its housing's inside would see the average of its group, with the housing's
// dimmer parts): hence the near-field strips above, each lit strip an unknown or a cell.
// A group's flat B would average very uneven direct light (a wall beside a lamp), so each
// group is also split into direct-light cells, a finer cut of the same trees with
// kDirectCellsPerUnknown times the groups' budget: each cell gets its own direct light after
// the solve (solver/formfactor/cell_direct.h), the group's reflected light stays shared.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/mesh/patch_clusters.h"
#include "solver/mesh/subdivide.h"

namespace radflux {

inline constexpr double kSplitEdge = 1.5;
inline constexpr double kMaxExtent = 2.0;
inline constexpr double kMaxConeDegrees = 30.0;
inline constexpr double kConeWeight = 2.0;
inline constexpr int64_t kDirectCellsPerUnknown = 16;

// Whether SubdivideAndGroup (solver/grouped_mesh.h) groups faces for these options: group_faces,
// and a target patch count (not --max-edge) no larger than the scene's face count.
bool GroupsFaces(const Scene& scene, const MeshOptions& options);

// What the emitters' direct light does to a patch (solver/formfactor/direct_lit.h probes it):
// groups never mix kLit with kUnlit patches, and a kBright patch is an unknown of its own.
enum class DirectLight : uint8_t {
  kUnlit = 0,   // no light sample arrived (and emitters, hidden patches)
  kLit = 1,     // some light sample arrived unoccluded, both cosines positive
  kBright = 2,  // lit, and its reflected direct light rho D (summed over bands) exceeds
                // kBrightReflector times the emitted power per unit of the scene's area, and
                // rho D A at least kBrightReflectorPower of the emitted power
};

// The patches of a scene that GroupsFaces: its faces split as above (edges of kSplitEdge
// sqrt(a*), faces of a* or more cut along their contacts), before the probe and the grouping
// (solver/grouped_mesh.h's SubdivideAndGroup does both).
// `cuts` as SubdivideScene's.
absl::StatusOr<PatchMesh> SubdivideForGrouping(const Scene& scene, const MeshOptions& options,
                                               const QuadCutsByFace& cuts = {});

// Groups the patches of `mesh` (of `scene`) into `unknowns` unknowns (or more: at least one
// per emitting, hidden or kBright patch and per (object, material, two-sidedness, side,
// `light`); or fewer: when every group is one patch) by the rule above; `light` per patch
// (ProbeDirectLight), or empty: every patch unlit. A group never spans two objects, so per-object
// means stay each object's own. With `cells`, also the direct-light cells: the same cut with
// kDirectCellsPerUnknown times the budget of non-emitting groups, a refinement of the groups
// (every cell's patches lie in one group).
PatchClusters GroupPatches(const Scene& scene, const PatchMesh& mesh, int64_t unknowns,
                           PatchClusters* cells = nullptr,
                           const std::vector<DirectLight>& light = {});

}  // namespace radflux
