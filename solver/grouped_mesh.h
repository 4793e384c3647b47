// A job's patches and unknowns: the mesh, and when the faces are grouped (mesh/face_grouping.h)
// the groups and direct-light cells, found with the emitters' direct light on each patch
// (formfactor/direct_lit.h) through an Embree scene of the patches that the job keeps.
#pragma once

#include <memory>

#include "absl/status/statusor.h"
#include "solver/mesh/face_grouping.h"
#include "solver/mesh/patch_clusters.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux {

struct GroupedMesh {
  PatchMesh mesh;          // the patches (what outputs draw)
  PatchClusters clusters;  // the unknowns; empty when the faces were not grouped
  PatchClusters cells;     // the direct-light cells; each lies inside one unknown (an
                           // emitter is a cell of its own); empty when not grouped
  std::unique_ptr<EmbreeRayCaster> caster;  // grouped: the probe's rays, on `mesh`
  double caster_seconds = 0;                // building `caster` (the job's Embree phase)
  double seconds = 0;                       // SubdivideAndGroup's whole time, caster included
};

// The scene's patches and unknowns, quads near emitters cut into strips across their light and
// along their outlines (formfactor/near_field_cuts.h): with GroupsFaces, split
// (SubdivideForGrouping), probed (ProbeDirectLight) and grouped (GroupPatches) to about
// options.target_patches unknowns (the same for every caller: the probe's seed is fixed); otherwise
// SubdivideScene's mesh, one unknown per patch.
absl::StatusOr<GroupedMesh> SubdivideAndGroup(const Scene& scene, const MeshOptions& options);

}  // namespace radflux
