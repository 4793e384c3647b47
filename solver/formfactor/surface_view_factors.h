// View factors between whole named surfaces, aggregated from patch rows (area-weighted):
// F_ST = sum_{i in S} A_i sum_{j in T} F_ij / A_S. What radiative heat-transfer users want.
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
  std::vector<std::vector<double>> factor;  // factor[s][t] = F from surface s to t
};

// `rows` must hold a row for every patch (build with needs_row all set).
SurfaceViewFactors AggregateViewFactors(const Scene& scene, const PatchMesh& mesh,
                                        const CsrMatrix& rows, SurfaceGrouping by);

// Header `from,NAME1,NAME2,...`, then one row per surface.
absl::Status WriteViewFactorsCsv(const std::string& path, const SurfaceViewFactors& factors);

}  // namespace radflux
