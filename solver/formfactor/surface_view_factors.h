// View factors between whole named surfaces, aggregated from patch rows (area-weighted):
// F_ST = sum_{i in S} A_i sum_{j in T} F_ij / A_S. What radiative heat-transfer users want.
// A_i is a patch's opaque area (Patch::opacity times its area), as the rows' F_ij to a
// partly transparent patch are the share its opaque part intercepts (surface_rows.h).
// Obstruction-only faces (Face::obstruction) belong to no surface: they block, nothing more.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"
#include "solver/sparse/csr_matrix.h"

namespace radflux {

enum class SurfaceGrouping { kObject, kGroup, kFace };

struct SurfaceViewFactors {
  std::vector<std::string> names;           // one per surface, in first-appearance order
  std::vector<double> area;                 // opaque area, m^2, one per surface
  std::vector<double> emittance;            // 1 - reflectance (band 0) of its first face
  std::vector<std::vector<double>> factor;  // factor[s][t] = F from surface s to t
};

// `rows` must hold a row for every patch that is not on an obstruction face.
SurfaceViewFactors AggregateViewFactors(const Scene& scene, const PatchMesh& mesh,
                                        const CsrMatrix& rows, SurfaceGrouping by);

}  // namespace radflux
