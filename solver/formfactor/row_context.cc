#include "solver/formfactor/row_context.h"

#include <algorithm>

#include "solver/formfactor/row_rays.h"

namespace radflux {

RowContext MakeRowContext(const PatchMesh& mesh, const PatchAttributes& attributes,
                          const RayCaster& caster, const PatchClusters* clusters,
                          const PatchClusters* cells) {
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
  context.opaque_area = attributes.area;
  context.mean_row_area = MeanRowArea(context.opaque_area, context.needs_row);
  if (context.clusters != nullptr && cells != nullptr && !cells->empty()) {
    context.cells = cells;
    context.cell_first.assign(n + 1, 0);
    for (uint32_t c = 0; c < cells->size(); ++c) {
      ++context.cell_first[context.UnknownOf(cells->Members(c)[0]) + 1];
    }
    for (size_t u = 0; u < n; ++u) context.cell_first[u + 1] += context.cell_first[u];
    context.cell_order.resize(cells->size());
    std::vector<uint32_t> next(context.cell_first.begin(), context.cell_first.end() - 1);
    for (uint32_t c = 0; c < cells->size(); ++c) {
      context.cell_order[next[context.UnknownOf(cells->Members(c)[0])]++] = c;
    }
  }
  return context;
}

uint32_t RowContext::RowRays(uint32_t u, int k) const {
  return RowRayCount(k, OpaqueArea(u), mean_row_area, Emits(u));
}

double RowContext::MaxRowSum(uint32_t u) const {
  const double rho = u < reflectance.size() ? reflectance[u] : 1.0;
  return std::max(1.0, kMaxRowGain / rho);
}

}  // namespace radflux
