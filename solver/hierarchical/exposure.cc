#include "solver/hierarchical/exposure.h"

#include "solver/core/sampling.h"

namespace radflux {

double ExposedFraction(const Element& e, const PatchMesh& mesh, const RayCaster& caster,
                       int samples, uint32_t pattern, double ray_epsilon) {
  const Frame frame = Frame::FromNormal(e.normal);
  const uint32_t direction_pattern = pattern ^ 0x9e3779b9u;
  int exposed = 0;
  for (int m = 0; m < samples; ++m) {
    const Vec3 x = SampleElementPoint(e, MultiJitteredSample(m, samples, pattern));
    const Vec3 d =
        frame.ToWorld(SampleCosineHemisphere(MultiJitteredSample(m, samples, direction_pattern)));
    const Hit hit = caster.Intersect({x + e.normal * ray_epsilon, d});
    if (hit.patch == kNoPatch || Dot(mesh.patches[hit.patch].normal, d) < 0) ++exposed;
  }
  return static_cast<double>(exposed) / samples;
}

}  // namespace radflux
