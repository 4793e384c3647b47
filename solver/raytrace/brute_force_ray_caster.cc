#include "solver/raytrace/brute_force_ray_caster.h"

namespace radflux {
namespace {

// Moeller-Trumbore; returns t or a negative value on a miss.
double IntersectTriangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = Cross(ray.direction, e2);
  const double det = Dot(e1, p);
  if (det == 0) return -1;
  const Vec3 s = ray.origin - a;
  const double u = Dot(s, p) / det;
  if (u < 0 || u > 1) return -1;
  const Vec3 q = Cross(s, e1);
  const double v = Dot(ray.direction, q) / det;
  if (v < 0 || u + v > 1) return -1;
  return Dot(e2, q) / det;
}

}  // namespace

Hit BruteForceRayCaster::Intersect(const Ray& ray) const {
  Hit best;
  double best_t = ray.t_far;
  // As traced in single precision, so that PassesThrough decides as it does in Embree.
  const float origin[3] = {static_cast<float>(ray.origin.x), static_cast<float>(ray.origin.y),
                           static_cast<float>(ray.origin.z)};
  const float direction[3] = {static_cast<float>(ray.direction.x),
                              static_cast<float>(ray.direction.y),
                              static_cast<float>(ray.direction.z)};
  for (uint32_t p = 0; p < mesh_.size(); ++p) {
    const Patch& patch = mesh_.patches[p];
    const Vec3 &a = mesh_.positions[patch.v[0]], &b = mesh_.positions[patch.v[1]],
               &c = mesh_.positions[patch.v[2]], &d = mesh_.positions[patch.v[3]];
    for (double t : {IntersectTriangle(ray, a, b, c), IntersectTriangle(ray, a, c, d)}) {
      const bool back = Dot(ray.direction, Cross(b - a, c - a)) >= 0;
      if (t > ray.t_near && t < best_t && !(patch.two_sided && back) &&
          !PassesThrough(origin, direction, p, patch.opacity)) {
        best_t = t;
        best = {p, t, 0, 0, Cross(b - a, c - a)};  // ccw vertices: towards the front
      }
    }
  }
  return best;
}

bool BruteForceRayCaster::Occluded(const Ray& ray) const {
  return Intersect(ray).patch != kNoPatch;
}

}  // namespace radflux
