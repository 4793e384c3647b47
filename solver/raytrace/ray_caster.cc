#include "solver/raytrace/ray_caster.h"

#include <bit>
#include <limits>

namespace radflux {
namespace {

// SplitMix64's finaliser: every input bit moves every output bit.
uint64_t Mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

bool PassesThrough(const float origin[3], const float direction[3], uint32_t patch,
                   float opacity) {
  if (!(opacity < 1)) return false;
  uint64_t h = Mix(0x9e3779b97f4a7c15ULL ^ patch);
  for (int k = 0; k < 3; ++k) {
    h = Mix(h ^ std::bit_cast<uint32_t>(origin[k]));
    h = Mix(h ^ (uint64_t{std::bit_cast<uint32_t>(direction[k])} << 32));
  }
  const double u = static_cast<double>(h >> 11) * 0x1p-53;  // uniform in [0, 1)
  return u >= opacity;
}

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
