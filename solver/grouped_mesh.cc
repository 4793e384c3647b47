#include "solver/grouped_mesh.h"

#include <chrono>
#include <utility>

#include "solver/core/seconds_since.h"
#include "solver/formfactor/direct_lit.h"
#include "solver/formfactor/near_field_cuts.h"

namespace radflux {

absl::StatusOr<GroupedMesh> SubdivideAndGroup(const Scene& scene, const MeshOptions& options) {
  const auto begin = std::chrono::steady_clock::now();
  GroupedMesh out;
  absl::StatusOr<QuadCutsByFace> near_field = NearFieldCuts(scene);
  if (!near_field.ok()) return near_field.status();
  if (!GroupsFaces(scene, options)) {
    absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, options, *near_field);
    if (!mesh.ok()) return mesh.status();
    out.mesh = *std::move(mesh);
    out.seconds = SecondsSince(begin);
    return out;
  }
  absl::StatusOr<PatchMesh> mesh = SubdivideForGrouping(scene, options, *near_field);
  if (!mesh.ok()) return mesh.status();
  out.mesh = *std::move(mesh);
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> caster = EmbreeRayCaster::Create(out.mesh);
  if (!caster.ok()) return caster.status();
  out.caster = *std::move(caster);
  out.caster_seconds = SecondsSince(start);
  out.clusters = GroupPatches(scene, out.mesh, options.target_patches, &out.cells,
                              ProbeDirectLight(scene, out.mesh, *out.caster));
  out.seconds = SecondsSince(begin);
  return out;
}

}  // namespace radflux
