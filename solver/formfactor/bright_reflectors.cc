#include "solver/formfactor/bright_reflectors.h"

#include <numbers>

#include "solver/formfactor/light_sampling.h"
#include "solver/formfactor/light_tree.h"

namespace radflux {
namespace {

// pi H at x (normal n), H the unoccluded irradiance from the tree's emitters: the cut's
// importances (exact for the emitters near x, far-field estimates for nodes of far ones).
double UnoccludedImportance(const LightTree& tree, const Vec3& x, const Vec3& n) {
  const LightTree::Cut cut = tree.CutAt(x, n);
  if (cut.size == 1 && tree.OneChoice(cut)) {  // a root's share 1, not its contribution
    return EmitterImportance(tree.Shape(cut.nodes[0].node), x, n);
  }
  return cut.total;
}

}  // namespace

RowContext WithBrightReflectors(const RowContext& context) {
  RowContext out = context;
  const std::vector<EmitterShape> shapes = EmitterShapes(context);
  if (shapes.empty()) return out;
  double power = 0, area = 0;
  for (const EmitterShape& shape : shapes) power += shape.power;
  for (uint32_t u = 0; u < context.Unknowns(); ++u) area += context.Area(u);
  if (!(power > 0 && area > 0)) return out;
  const double bright = kBrightReflector * power / area;
  const LightTree tree(shapes);
  for (uint32_t u = 0; u < context.Unknowns(); ++u) {
    if (context.emitter[u] || !context.needs_row[u] || !context.SinglePatch(u)) continue;
    const Patch& patch = context.mesh->patches[context.FirstPatch(u)];
    if (patch.hidden) continue;
    const double rho = u < context.reflectance.size() ? context.reflectance[u] : 1.0;
    const double b =
        rho * UnoccludedImportance(tree, patch.centroid, patch.normal) / std::numbers::pi;
    if (!(b > bright && b * context.Area(u) > kBrightReflectorPower * power)) continue;
    out.emitter[u] = 1;
    if (out.emission.size() < out.emitter.size()) out.emission.resize(out.emitter.size(), 1.0);
    out.emission[u] = b;
  }
  return out;
}

}  // namespace radflux
