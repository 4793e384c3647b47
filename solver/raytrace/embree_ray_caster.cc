#include "solver/raytrace/embree_ray_caster.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstddef>
#include <limits>

namespace radflux {
namespace {

void OnEmbreeError(void*, RTCError code, const char* message) {
  spdlog::error("embree error {}: {}", static_cast<int>(code), message ? message : "");
}

float ToFloatFar(double t) {
  return t >= std::numeric_limits<float>::max() ? std::numeric_limits<float>::infinity()
                                                : static_cast<float>(t);
}

RTCRay ToRTCRay(const Ray& ray) {
  RTCRay r;
  r.org_x = static_cast<float>(ray.origin.x);
  r.org_y = static_cast<float>(ray.origin.y);
  r.org_z = static_cast<float>(ray.origin.z);
  r.dir_x = static_cast<float>(ray.direction.x);
  r.dir_y = static_cast<float>(ray.direction.y);
  r.dir_z = static_cast<float>(ray.direction.z);
  r.tnear = static_cast<float>(ray.t_near);
  r.tfar = ToFloatFar(ray.t_far);
  r.time = 0;
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  return r;
}

// StreamRay is traced in place as an RTCRayHit: the same fields at the same offsets.
static_assert(sizeof(StreamRay) == sizeof(RTCRayHit) && alignof(StreamRay) == alignof(RTCRayHit));
static_assert(offsetof(StreamRay, org_x) == offsetof(RTCRayHit, ray.org_x) &&
              offsetof(StreamRay, t_near) == offsetof(RTCRayHit, ray.tnear) &&
              offsetof(StreamRay, dir_x) == offsetof(RTCRayHit, ray.dir_x) &&
              offsetof(StreamRay, time) == offsetof(RTCRayHit, ray.time) &&
              offsetof(StreamRay, t_far) == offsetof(RTCRayHit, ray.tfar) &&
              offsetof(StreamRay, mask) == offsetof(RTCRayHit, ray.mask) &&
              offsetof(StreamRay, flags) == offsetof(RTCRayHit, ray.flags) &&
              offsetof(StreamRay, ng_x) == offsetof(RTCRayHit, hit.Ng_x) &&
              offsetof(StreamRay, u) == offsetof(RTCRayHit, hit.u) &&
              offsetof(StreamRay, prim) == offsetof(RTCRayHit, hit.primID) &&
              offsetof(StreamRay, geom) == offsetof(RTCRayHit, hit.geomID) &&
              offsetof(StreamRay, inst) == offsetof(RTCRayHit, hit.instID));
static_assert(kNoPatch == RTC_INVALID_GEOMETRY_ID);

// Rejects hits on the back of two-sided patches and the hits PassesThrough lets through
// partly transparent patches (user data: a PatchFilter per patch).
void FilterHits(const RTCFilterFunctionNArguments* args) {
  const auto* filter = static_cast<const EmbreeRayCaster::PatchFilter*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const EmbreeRayCaster::PatchFilter& patch = filter[RTCHitN_primID(args->hit, n, i)];
    const float direction[3] = {RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i),
                                RTCRayN_dir_z(args->ray, n, i)};
    const float facing = direction[0] * RTCHitN_Ng_x(args->hit, n, i) +
                         direction[1] * RTCHitN_Ng_y(args->hit, n, i) +
                         direction[2] * RTCHitN_Ng_z(args->hit, n, i);
    if (patch.two_sided && facing >= 0) {
      args->valid[i] = 0;
      continue;
    }
    const float origin[3] = {RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i),
                             RTCRayN_org_z(args->ray, n, i)};
    if (PassesThrough(origin, direction, RTCHitN_primID(args->hit, n, i), patch.opacity)) {
      args->valid[i] = 0;
    }
  }
}

}  // namespace

RTCDevice SharedEmbreeDevice() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice("verbose=0");
    if (d) rtcSetDeviceErrorFunction(d, OnEmbreeError, nullptr);
    return d;
  }();
  return device;
}

absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> EmbreeRayCaster::Create(const PatchMesh& mesh) {
  RTCDevice device = SharedEmbreeDevice();
  if (!device) return absl::InternalError("cannot create the Embree device");
  RTCScene scene = rtcNewScene(device);
  // Medium (binned SAH, no spatial splits): our patches are uniform quads, for which the
  // high-quality build's splits cost build time without faster traversal (measured: -1 ms of
  // a 48 ms 2,000-patch solve, equal at 10,000 patches).
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                              3 * sizeof(float), std::max<size_t>(1, mesh.positions.size())));
  auto* indices = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                              4 * sizeof(uint32_t), std::max<size_t>(1, mesh.patches.size())));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geometry);
    rtcReleaseScene(scene);
    return absl::ResourceExhaustedError("Embree could not allocate the patch buffers");
  }
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    vertices[3 * i] = static_cast<float>(mesh.positions[i].x);
    vertices[3 * i + 1] = static_cast<float>(mesh.positions[i].y);
    vertices[3 * i + 2] = static_cast<float>(mesh.positions[i].z);
  }
  std::vector<PatchFilter> filter(mesh.patches.size());
  bool any_filtered = false;
  for (size_t p = 0; p < mesh.patches.size(); ++p) {
    std::copy(mesh.patches[p].v.begin(), mesh.patches[p].v.end(), indices + 4 * p);
    filter[p] = {mesh.patches[p].two_sided, mesh.patches[p].opacity};
    any_filtered = any_filtered || filter[p].two_sided || filter[p].opacity < 1;
  }
  if (any_filtered) {
    rtcSetGeometryUserData(geometry, filter.data());  // moved into the caster: same buffer
    rtcSetGeometryIntersectFilterFunction(geometry, FilterHits);
    rtcSetGeometryOccludedFilterFunction(geometry, FilterHits);
  } else {
    filter.clear();
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
    rtcReleaseScene(scene);
    return absl::InternalError("Embree failed to build the scene (see log)");
  }
  return std::unique_ptr<EmbreeRayCaster>(new EmbreeRayCaster(scene, std::move(filter)));
}

EmbreeRayCaster::~EmbreeRayCaster() { rtcReleaseScene(scene_); }

Hit EmbreeRayCaster::Intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit;
  rayhit.ray = ToRTCRay(ray);
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  return {rayhit.hit.primID,
          rayhit.ray.tfar,
          rayhit.hit.u,
          rayhit.hit.v,
          {rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z}};
}

void EmbreeRayCaster::IntersectStream(std::span<StreamRay> rays) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1M(scene_, &context, reinterpret_cast<RTCRayHit*>(rays.data()),
                 static_cast<unsigned>(rays.size()), sizeof(StreamRay));
}

void EmbreeRayCaster::OccludedStream(std::span<StreamRay> rays) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  // The RTCRay part of each RTCRayHit-shaped StreamRay, at its stride.
  rtcOccluded1M(scene_, &context, reinterpret_cast<RTCRay*>(rays.data()),
                static_cast<unsigned>(rays.size()), sizeof(StreamRay));
}

bool EmbreeRayCaster::Occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = ToRTCRay(ray);
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0;
}

}  // namespace radflux
