#include "solver/formfactor/row_context.h"

#include <algorithm>

namespace radflux {

RowContext MakeRowContext(const PatchMesh& mesh, const PatchAttributes& attributes,
                          const RayCaster& caster, const PatchClusters* clusters) {
  RowContext context;
  context.mesh = &mesh;
  context.caster = &caster;
  context.clusters = clusters != nullptr && !clusters->empty() ? clusters : nullptr;
  context.ray_epsilon = RayEpsilonFor(mesh);
  const size_t n = attributes.size();
  context.needs_row.resize(n);
  context.emitter.resize(n);
  context.emission.resize(n);
  context.reflectance.resize(n);
  for (size_t p = 0; p < n; ++p) {
    context.reflectance[p] = MaxComponent(attributes.reflectance[p]);
    context.needs_row[p] = context.reflectance[p] > 0;
    context.emitter[p] = MaxComponent(attributes.emission[p]) > 0;
    for (int b = 0; b < kBands; ++b) context.emission[p] += attributes.emission[p][b];
  }
  return context;
}

double RowContext::MaxRowSum(uint32_t u) const {
  const double rho = u < reflectance.size() ? reflectance[u] : 1.0;
  return std::max(1.0, kMaxRowGain / rho);
}

}  // namespace radflux
