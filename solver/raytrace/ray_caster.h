// RayCaster: the ray queries radflux needs, against the patches of one mesh.
// EmbreeRayCaster is the fast one; BruteForceRayCaster checks it in tests. Both let a ray
// through a partly transparent patch (Patch::opacity < 1) as PassesThrough decides, in
// every query: a hit there is skipped and the ray goes on to what lies behind.
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
  Vec3 normal;         // geometric normal of the hit patch, unnormalised, towards its front
};

// One ray of a single-precision stream with room for its hit: what the row builders cast
// by the thousand per row, written in place (no conversion pass). Its layout is Embree's
// RTCRayHit (checked in embree_ray_caster.cc), so EmbreeRayCaster traces it as it is.
struct alignas(16) StreamRay {
  float org_x = 0, org_y = 0, org_z = 0, t_near = 0;
  float dir_x = 0, dir_y = 0, dir_z = 0, time = 0;
  float t_far = std::numeric_limits<float>::infinity();
  uint32_t mask = 0xffffffffu, id = 0, flags = 0;
  // The hit, filled by IntersectStream:
  float ng_x = 0, ng_y = 0, ng_z = 0;  // geometric normal as in Hit::normal
  float u = 0, v = 0;
  uint32_t prim = kNoPatch;  // the patch hit; meaningful only when geom != kNoPatch
  uint32_t geom = kNoPatch;  // kNoPatch when the ray escapes
  uint32_t inst = kNoPatch;

  void SetOrigin(const Vec3& o) {
    org_x = static_cast<float>(o.x), org_y = static_cast<float>(o.y),
    org_z = static_cast<float>(o.z);
  }
  void SetDirection(const Vec3& d) {
    dir_x = static_cast<float>(d.x), dir_y = static_cast<float>(d.y),
    dir_z = static_cast<float>(d.z);
  }
  // A shadow ray from `origin` to just short of `target`: t in (0, 1 - 1e-6) along
  // target - origin, so the target's own surface never occludes it.
  static StreamRay Segment(const Vec3& origin, const Vec3& target) {
    StreamRay ray;
    ray.SetOrigin(origin);
    ray.SetDirection(target - origin);
    ray.t_far = static_cast<float>(1 - 1e-6);
    return ray;
  }
  // Makes the ray ready to trace again (no hit yet, t_far back to infinity).
  void ResetHit() {
    t_far = std::numeric_limits<float>::infinity();
    geom = inst = kNoPatch;
  }
  // After OccludedStream: whether some patch lay in (t_near, t_far) (Embree's convention:
  // an occluded ray's t_far becomes -infinity).
  bool Occluded() const { return t_far < 0; }
  // The patch whose front side the ray hit; kNoPatch for a miss or a back side.
  uint32_t FrontPatch() const {
    return geom != kNoPatch && dir_x * ng_x + dir_y * ng_y + dir_z * ng_z < 0 ? prim : kNoPatch;
  }
};

// Whether the ray with single-precision `origin` and `direction` (as traced) passes through
// patch `patch` of opacity `opacity` (Patch::opacity) where it meets it: true with
// probability 1 - opacity, by a hash of the ray and the patch, never from shared random
// state, so the same ray always decides alike (rows stay bit-identical for any partition
// of the work) and different rays decide independently. Always false at opacity 1.
bool PassesThrough(const float origin[3], const float direction[3], uint32_t patch,
                   float opacity);

class RayCaster {
 public:
  virtual ~RayCaster() = default;
  // Nearest patch hit in (t_near, t_far), either side of it.
  virtual Hit Intersect(const Ray& ray) const = 0;
  // True when any patch lies in (t_near, t_far).
  virtual bool Occluded(const Ray& ray) const = 0;

  // Intersect on every ray of the stream, with its hit written into it (t_far becomes the
  // hit distance); an implementation may trace them as a stream. The default loops.
  virtual void IntersectStream(std::span<StreamRay> rays) const;
  // Occluded on every ray of the stream, answered in place (StreamRay::Occluded); an
  // implementation may trace them as a stream. The default loops.
  virtual void OccludedStream(std::span<StreamRay> rays) const;
};

}  // namespace radflux
