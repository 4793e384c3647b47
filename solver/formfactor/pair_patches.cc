#include "solver/formfactor/pair_patches.h"

#include <cmath>

namespace radflux {

PairPatches::PairPatches(const PatchMesh& mesh) {
  patch_.resize(mesh.size());
  sampler_.reserve(mesh.size());
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& source = mesh.patches[p];
    PairPatch& patch = patch_[p];
    for (size_t k = 0; k < 4; ++k) patch.corner[k] = mesh.positions[source.v[k]];
    patch.centroid = source.centroid;
    patch.normal = source.normal;
    patch.front_margin = 1e-9 * std::sqrt(source.area);
    patch.corners = static_cast<uint32_t>(source.VertexCount());
    sampler_.emplace_back(mesh, p);
  }
}

}  // namespace radflux
