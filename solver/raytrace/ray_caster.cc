#include "solver/raytrace/ray_caster.h"

namespace radflux {

void RayCaster::IntersectStream(std::span<StreamRay> rays) const {
  for (StreamRay& r : rays) {
    const Hit hit =
        Intersect({{r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, r.t_near, r.t_far});
    if (hit.patch == kNoPatch) continue;
    r.t_far = static_cast<float>(hit.t);
    r.ng_x = static_cast<float>(hit.normal.x);
    r.ng_y = static_cast<float>(hit.normal.y);
    r.ng_z = static_cast<float>(hit.normal.z);
    r.u = hit.u;
    r.v = hit.v;
    r.prim = hit.patch;
    r.geom = 0;
  }
}

void RayCaster::OccludedBatch(std::span<const Ray> rays, std::span<uint8_t> occluded) const {
  for (size_t k = 0; k < rays.size(); ++k) occluded[k] = Occluded(rays[k]);
}

}  // namespace radflux
