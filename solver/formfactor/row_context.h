// Building the RowContext of a mesh from its patch attributes.
#pragma once

#include "solver/formfactor/row_builder.h"
#include "solver/mesh/patch_attributes.h"

namespace radflux {

// Rows only where rho > 0 in some band; emitters where E > 0 in some band. `attributes` are
// per unknown: per patch, or per group of `clusters` when it is given and not empty; `cells`
// (grouped only; each inside one group) are the groups' direct-light cells.
RowContext MakeRowContext(const PatchMesh& mesh, const PatchAttributes& attributes,
                          const RayCaster& caster, const PatchClusters* clusters = nullptr,
                          const PatchClusters* cells = nullptr);

}  // namespace radflux
