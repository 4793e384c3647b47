// BruteForceRayCaster: tests every patch for every ray, in double precision.
// O(n) per ray; it exists to check EmbreeRayCaster and the row builders in tests.
#pragma once

#include "solver/mesh/patch_mesh.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

class BruteForceRayCaster final : public RayCaster {
 public:
  explicit BruteForceRayCaster(const PatchMesh& mesh) : mesh_(mesh) {}
  Hit Intersect(const Ray& ray) const override;
  bool Occluded(const Ray& ray) const override;

 private:
  const PatchMesh& mesh_;
};

}  // namespace radflux
