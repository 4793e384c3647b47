// Per-vertex values of a PatchMesh, for Gouraud shading and mesh export. A vertex takes
// the area-weighted mean of the patches that use it; since PatchMesh never shares a
// vertex between faces, the mean stays inside one source face and creases stay sharp.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/core/vec3.h"
#include "solver/mesh/patch_mesh.h"

namespace radflux {

// Radiosity per vertex (W/m^2 per band) from radiosity per patch; one entry per
// mesh.positions, zero for a vertex no patch uses. Fails if the sizes disagree.
absl::StatusOr<std::vector<Rgb>> VertexRadiosity(const PatchMesh& mesh,
                                                 const std::vector<Rgb>& patch_radiosity);

// Unit normal per vertex: the normal of the (single) face whose patches use it;
// +z for a vertex no patch uses.
std::vector<Vec3> VertexNormals(const PatchMesh& mesh);

}  // namespace radflux
