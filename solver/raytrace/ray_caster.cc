#include "solver/raytrace/ray_caster.h"

namespace radflux {

void RayCaster::IntersectBatch(std::span<const Ray> rays, std::span<Hit> hits) const {
  for (size_t k = 0; k < rays.size(); ++k) hits[k] = Intersect(rays[k]);
}

void RayCaster::OccludedBatch(std::span<const Ray> rays, std::span<uint8_t> occluded) const {
  for (size_t k = 0; k < rays.size(); ++k) occluded[k] = Occluded(rays[k]);
}

}  // namespace radflux
