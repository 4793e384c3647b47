// Final gather: a view-dependent second pass over a radiosity solution (the two-pass method).
// Each pixel averages P = min(N, max(16, N / 8)) multi-jittered points of the pixel, N the
// gather rays per pixel: a point's primary ray goes to the visible point x on patch p (front
// side; a miss or a back side gives black), which estimates
//     L(x) = E_p / pi + rho_p / pi * (H_direct(x) + H_indirect(x))
// with
//   H_direct   = sum_j E_j F_j(x) V: one light sample on the emitters (LightSampler, as the
//                emitter columns of monte_carlo's rows are sampled, over the emitting faces
//                merged by MakeGatherLights), shadow ray included;
//   H_indirect = the mean, over the point's N / P gather rays (cosine-weighted from x), of the
//                reflected radiosity R = B - E (Gouraud-interpolated, at least 0) where the ray
//                meets a front side (0 on a miss or a back side): its expectation is the
//                irradiance from everything but the emitters' own emission, which H_direct
//                already counts, so nothing is counted twice.
// In a closed enclosure with B the exact solution, the expectation of L(x) is B_p / pi.
// Seeds are per pixel (seed, y * width + x): the image does not depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/camera.h"
#include "solver/output/image.h"
#include "solver/output/shading_mesh.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

struct GatherOptions {
  int rays = 16;      // N: gather rays per pixel (P points of the pixel with a light sample each)
  int threads = 0;    // 0 = all cores; the image does not depend on it
  uint64_t seed = 1;  // the pixels' sample patterns are seeded from (seed, pixel index)
};

// Radiance image (W/m^2/sr per band) of the scene whose patches have `attributes` and
// radiosity `patch_radiosity` (W/m^2 per band), seen by `camera`, by final gathering with
// rays cast by `caster` (which must report Embree's u,v: EmbreeRayCaster does); R is
// interpolated from its values at `shading`'s welded vertices (VertexRadiosity).
// INVALID_ARGUMENT for sizes that disagree, a bad camera, or rays outside [1, 4096].
absl::StatusOr<Image> RenderFinalGather(const PatchMesh& mesh, const ShadingMesh& shading,
                                        const RayCaster& caster, const PatchAttributes& attributes,
                                        const std::vector<Rgb>& patch_radiosity,
                                        const Camera& camera, const GatherOptions& options);

// The same engine without gather rays: the direct light per pixel over the interpolated rest.
// Each pixel averages options.rays multi-jittered points (`rays` here counts points, each with
// one primary ray and one light sample); a point x on patch p shows
//     L(x) = (E_p + I(x) + rho_p H_direct(x)) / pi,
// H_direct = sum_j E_j F_j(x) V by one light sample as above, and I the indirect radiosity
// Gouraud-interpolated from its per-patch values: gathered afresh for the patches the picture
// shows (RegatherShownIndirect, indirect_regather.h; seeded by options.seed), `patch_indirect`
// (the solve's, solve/indirect_light.h) for the rest. Where the light falls off or is shadowed
// within a patch, the picture follows it at the pixel, not at the patch. The rest as
// RenderFinalGather.
absl::StatusOr<Image> RenderDirectPerPixel(const PatchMesh& mesh, const ShadingMesh& shading,
                                           const RayCaster& caster,
                                           const PatchAttributes& attributes,
                                           const std::vector<Rgb>& patch_radiosity,
                                           const std::vector<Rgb>& patch_indirect,
                                           const Camera& camera, const GatherOptions& options);

}  // namespace radflux
