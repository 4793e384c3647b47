#include "solver/formfactor/row_context.h"

namespace radflux {

RowContext MakeRowContext(const PatchMesh& mesh, const PatchAttributes& attributes,
                          const RayCaster& caster) {
  RowContext context;
  context.mesh = &mesh;
  context.caster = &caster;
  context.ray_epsilon = RayEpsilonFor(mesh);
  context.needs_row.resize(mesh.size());
  context.emitter.resize(mesh.size());
  context.emission.resize(mesh.size());
  for (size_t p = 0; p < mesh.size(); ++p) {
    context.needs_row[p] = MaxComponent(attributes.reflectance[p]) > 0;
    context.emitter[p] = MaxComponent(attributes.emission[p]) > 0;
    for (int b = 0; b < kBands; ++b) context.emission[p] += attributes.emission[p][b];
  }
  return context;
}

}  // namespace radflux
