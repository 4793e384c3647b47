#include "solver/hierarchical/exposure.h"

#include <span>

#include "solver/core/sampling.h"

namespace radflux {

double ExposedFraction(const Element& e, const PatchMesh& mesh, const RayCaster& caster,
                       int samples, uint32_t pattern, double ray_epsilon) {
  const Frame frame = Frame::FromNormal(e.normal);
  const uint32_t direction_pattern = pattern ^ 0x9e3779b9u;
  const MultiJitteredSets<2> drawn({pattern, direction_pattern}, static_cast<size_t>(samples));
  const std::span<const Point2> points = drawn[0], directions = drawn[1];
  int exposed = 0;
  for (int m = 0; m < samples; ++m) {
    const Vec3 x = SampleElementPoint(e, points[m]);
    const Vec3 d = frame.ToWorld(SampleCosineHemisphere(directions[m]));
    const Hit hit = caster.Intersect({x + e.normal * ray_epsilon, d});
    if (hit.patch == kNoPatch) {
      ++exposed;
      continue;
    }
    const Patch& patch = mesh.patches[hit.patch];
    if (Dot(patch.normal, d) < 0 || patch.opacity < 1) ++exposed;
  }
  return static_cast<double>(exposed) / samples;
}

}  // namespace radflux
