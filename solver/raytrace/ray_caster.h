// RayCaster: the two ray queries radflux needs, against the patches of one mesh.
// EmbreeRayCaster is the fast one; BruteForceRayCaster checks it in tests.
#pragma once

#include <cstdint>
#include <limits>
#include <span>

#include "solver/core/vec3.h"

namespace radflux {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // need not be unit length; t is in units of |direction|
  double t_near = 0;
  double t_far = std::numeric_limits<double>::infinity();
};

inline constexpr uint32_t kNoPatch = 0xffffffffu;

struct Hit {
  uint32_t patch = kNoPatch;  // kNoPatch when the ray escapes
  double t = 0;
  float u = 0, v = 0;  // Embree's parametric coordinates on the hit primitive
};

class RayCaster {
 public:
  virtual ~RayCaster() = default;
  // Nearest patch hit in (t_near, t_far), either side of it.
  virtual Hit Intersect(const Ray& ray) const = 0;
  // True when any patch lies in (t_near, t_far).
  virtual bool Occluded(const Ray& ray) const = 0;

  // Many rays at once (hits.size() == rays.size()): the same answers as Intersect on each
  // ray, but an implementation may trace them as a stream. The default loops.
  virtual void IntersectBatch(std::span<const Ray> rays, std::span<Hit> hits) const;
  // occluded[k] = Occluded(rays[k]), possibly as a stream.
  virtual void OccludedBatch(std::span<const Ray> rays, std::span<uint8_t> occluded) const;
};

}  // namespace radflux
