#include "solver/scene/recentre.h"

#include <algorithm>
#include <cmath>

namespace radflux {

Vec3 RecentringOffset(const Vec3& lo, const Vec3& hi) {
  const double diagonal = Length(hi - lo);
  if (!(diagonal > 0) || !std::isfinite(diagonal)) return {};
  const double q = std::exp2(std::ceil(std::log2(4 * diagonal)));
  const Vec3 centre = (lo + hi) / 2;
  return {std::round(centre.x / q) * q, std::round(centre.y / q) * q, std::round(centre.z / q) * q};
}

void RecentreScene(Scene& scene) {
  if (scene.positions.empty()) return;
  Vec3 lo = scene.positions[0], hi = lo;
  for (const Vec3& p : scene.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const Vec3 offset = RecentringOffset(lo, hi);
  if (offset == Vec3{}) return;
  for (Vec3& p : scene.positions) p = p - offset;
  scene.origin += offset;
}

}  // namespace radflux
