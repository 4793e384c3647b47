#include "solver/raytrace/ray_caster.h"

#include <limits>

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

void RayCaster::OccludedStream(std::span<StreamRay> rays) const {
  for (StreamRay& r : rays) {
    if (Occluded({{r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, r.t_near, r.t_far})) {
      r.t_far = -std::numeric_limits<float>::infinity();
    }
  }
}

}  // namespace radflux
