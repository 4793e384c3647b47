// EmbreeRayCaster: one Embree 3 device per process and one scene per mesh. Every
// patch is a quad primitive (a triangle repeats its last vertex); primID = patch index.
// Embree errors are routed to spdlog; construction fails with a Status, never throws.
// Hits on the back of a two-sided patch (Patch::two_sided) are ignored by a filter
// function, so its back-face twin is what a ray meets from behind and the twins never
// shade each other; the same filter skips the hits PassesThrough lets through partly
// transparent patches. A mesh without either gets no filter.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

class EmbreeRayCaster final : public RayCaster {
 public:
  static absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> Create(const PatchMesh& mesh);
  ~EmbreeRayCaster() override;
  EmbreeRayCaster(const EmbreeRayCaster&) = delete;
  EmbreeRayCaster& operator=(const EmbreeRayCaster&) = delete;

  Hit Intersect(const Ray& ray) const override;
  bool Occluded(const Ray& ray) const override;
  // Traced with Embree's stream API (rtcIntersect1M / rtcOccluded1M).
  void IntersectStream(std::span<StreamRay> rays) const override;
  void OccludedStream(std::span<StreamRay> rays) const override;

  RTCScene scene() const { return scene_; }

  // What the hit filter needs of a patch.
  struct PatchFilter {
    bool two_sided = false;  // Patch::two_sided: hits on its back are skipped
    float opacity = 1;       // Patch::opacity
  };

 private:
  EmbreeRayCaster(RTCScene scene, std::vector<PatchFilter> filter)
      : scene_(scene), filter_(std::move(filter)) {}
  RTCScene scene_;
  std::vector<PatchFilter> filter_;  // per patch, the filter's user data (empty: no filter)
};

// The process-wide Embree device (created on first use).
RTCDevice SharedEmbreeDevice();

}  // namespace radflux
