// Embree on demand: the client executables' own definitions of the Embree functions the
// solver calls. Each loads libembree3 (and with it TBB) the first time one of them is called,
// so a service verb that renders nothing never does (~4 ms of a process start:
// bench/RESULTS.md, "Service overhead (issue 4)"), and `radflux solve` loads it at its first
// Embree call. radflux-local and radflux-service link --as-needed, and the ctests
// `radflux-local_loads_embree_on_demand` and `radflux-service_loads_embree_on_demand` check
// that they do not name libembree3: a solver change that calls an Embree function missing
// here fails them.
#include <dlfcn.h>
#include <embree3/rtcore.h>

#include <cstdio>
#include <cstdlib>

namespace {

// The library, loaded once; a clear message and exit status 1 if it cannot be.
void* Embree() {
  static void* const handle = [] {
    void* h = dlopen("libembree3.so.3", RTLD_LAZY | RTLD_LOCAL);
    if (h == nullptr) {
      std::fprintf(stderr, "radflux: cannot load Embree (libembree3.so.3): %s\n", dlerror());
      std::exit(1);
    }
    return h;
  }();
  return handle;
}

template <typename Function>
Function Lookup(const char* name) {
  void* f = dlsym(Embree(), name);
  if (f == nullptr) {
    std::fprintf(stderr, "radflux: Embree has no %s: %s\n", name, dlerror());
    std::exit(1);
  }
  return reinterpret_cast<Function>(f);
}

}  // namespace

// Defines `name` with Embree's own signature, forwarding to the loaded library's.
#define RADFLUX_EMBREE_ON_DEMAND(ret, name, params, args)    \
  ret name params {                                          \
    static const auto real = Lookup<decltype(&name)>(#name); \
    return real args;                                        \
  }

extern "C" {
RADFLUX_EMBREE_ON_DEMAND(RTCDevice, rtcNewDevice, (const char* config), (config))
RADFLUX_EMBREE_ON_DEMAND(void, rtcSetDeviceErrorFunction,
                         (RTCDevice device, RTCErrorFunction error, void* user),
                         (device, error, user))
RADFLUX_EMBREE_ON_DEMAND(RTCError, rtcGetDeviceError, (RTCDevice device), (device))
RADFLUX_EMBREE_ON_DEMAND(RTCScene, rtcNewScene, (RTCDevice device), (device))
RADFLUX_EMBREE_ON_DEMAND(void, rtcSetSceneBuildQuality, (RTCScene scene, RTCBuildQuality quality),
                         (scene, quality))
RADFLUX_EMBREE_ON_DEMAND(RTCGeometry, rtcNewGeometry, (RTCDevice device, RTCGeometryType type),
                         (device, type))
RADFLUX_EMBREE_ON_DEMAND(void*, rtcSetNewGeometryBuffer,
                         (RTCGeometry geometry, RTCBufferType type, unsigned int slot,
                          RTCFormat format, size_t stride, size_t count),
                         (geometry, type, slot, format, stride, count))
RADFLUX_EMBREE_ON_DEMAND(void, rtcSetGeometryUserData, (RTCGeometry geometry, void* user),
                         (geometry, user))
RADFLUX_EMBREE_ON_DEMAND(void, rtcSetGeometryIntersectFilterFunction,
                         (RTCGeometry geometry, RTCFilterFunctionN filter), (geometry, filter))
RADFLUX_EMBREE_ON_DEMAND(void, rtcSetGeometryOccludedFilterFunction,
                         (RTCGeometry geometry, RTCFilterFunctionN filter), (geometry, filter))
RADFLUX_EMBREE_ON_DEMAND(void, rtcCommitGeometry, (RTCGeometry geometry), (geometry))
RADFLUX_EMBREE_ON_DEMAND(unsigned int, rtcAttachGeometry, (RTCScene scene, RTCGeometry geometry),
                         (scene, geometry))
RADFLUX_EMBREE_ON_DEMAND(void, rtcReleaseGeometry, (RTCGeometry geometry), (geometry))
RADFLUX_EMBREE_ON_DEMAND(void, rtcCommitScene, (RTCScene scene), (scene))
RADFLUX_EMBREE_ON_DEMAND(void, rtcReleaseScene, (RTCScene scene), (scene))
RADFLUX_EMBREE_ON_DEMAND(void, rtcIntersect1,
                         (RTCScene scene, RTCIntersectContext* context, RTCRayHit* rayhit),
                         (scene, context, rayhit))
RADFLUX_EMBREE_ON_DEMAND(void, rtcIntersect1M,
                         (RTCScene scene, RTCIntersectContext* context, RTCRayHit* rayhit,
                          unsigned int count, size_t stride),
                         (scene, context, rayhit, count, stride))
RADFLUX_EMBREE_ON_DEMAND(void, rtcOccluded1,
                         (RTCScene scene, RTCIntersectContext* context, RTCRay* ray),
                         (scene, context, ray))
RADFLUX_EMBREE_ON_DEMAND(void, rtcOccluded1M,
                         (RTCScene scene, RTCIntersectContext* context, RTCRay* ray,
                          unsigned int count, size_t stride),
                         (scene, context, ray, count, stride))
}
