// EmbreeRayCaster: one Embree 3 device per process and one scene per mesh. Every
// patch is a quad primitive (a triangle repeats its last vertex); primID = patch index.
// Embree errors are routed to spdlog; construction fails with a Status, never throws.
#pragma once

#include <embree3/rtcore.h>

#include <memory>

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

 private:
  explicit EmbreeRayCaster(RTCScene scene) : scene_(scene) {}
  RTCScene scene_;
};

// The process-wide Embree device (created on first use).
RTCDevice SharedEmbreeDevice();

}  // namespace radflux
