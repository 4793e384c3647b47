// ExportMesh: the lit mesh the writers (PLY, glTF) emit: welded vertices (shading_mesh.h)
// with their smooth normals and radiosity, and one polygon per patch whose outline has the
// T-junction vertices of its edges inserted, so that neighbouring polygons share every
// vertex along a common edge and viewers show neither seams nor cracks.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/shading_mesh.h"

namespace radflux {

struct ExportMesh {
  std::vector<Vec3> positions;             // scene units
  std::vector<Vec3> normals;               // unit
  std::vector<Rgb> radiosity;              // W/m^2 per band
  std::vector<uint32_t> polygon_first;     // polygon i: polygon_vertices[first[i], first[i+1])
  std::vector<uint32_t> polygon_vertices;  // counter-clockwise seen from the lit side

  size_t polygons() const { return polygon_first.empty() ? 0 : polygon_first.size() - 1; }
};

// The export mesh of `mesh` lit by `patch_radiosity` (one Rgb per patch, W/m^2): vertex i
// is welded vertex i of `shading`, polygon p is patch p. Fails on a size mismatch.
absl::StatusOr<ExportMesh> BuildExportMesh(const PatchMesh& mesh, const ShadingMesh& shading,
                                           const std::vector<Rgb>& patch_radiosity);

// Triangle indices of `m`: triangles as they are, quads as (v0,v1,v3) and (v2,v3,v1) (as
// Embree and the render split them), larger polygons (a patch with T-junctions) as a fan
// around a centre vertex appended to `m` (mean position, normal and radiosity of the
// polygon's vertices), since a fan from a corner would make zero-area triangles.
std::vector<uint32_t> TriangulateExportMesh(ExportMesh& m);

}  // namespace radflux
