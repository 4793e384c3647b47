// The indirect light of the patches a picture shows, gathered afresh from the solution: what
// the default picture (RenderDirectPerPixel) Gouraud-shades under its per-pixel direct light.
// A shown patch p casts cosine rays from stratified points of its own area into the solved
// scene and averages the reflected radiosity R = B - E they meet, Gouraud-interpolated (0 on a
// miss or a back side), an emitter's own reflection included:
//     I_p = rho_p * H_p,  H_p the mean irradiance over p from everything but emission,
// light that has bounced at least once. Against the solve's own I (solve/indirect_light.h) it
// reads its sources as smooth fields, not flat patches, and its noise is its own rays', not its
// row's: the Cornell box's defaults against Cycles went from 0.45% to 0.25% RMS per surface in
// one run, the ceiling's noise-free bias from -0.55% to -0.1% (bench/RESULTS.md); a grouped
// unknown's faces each get their own (a chair's seat and its underside). Rays follow what the
// picture shows: kRegatherRaysPerPixel per pixel whose centre sees the patch, within
// [kRegatherLeastRays, kRegatherMostRays]; a patch no pixel centre sees keeps the solve's I, so
// the cost follows the picture's size, not the scene's.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/camera.h"
#include "solver/output/vertex_radiosity.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

inline constexpr int kRegatherRaysPerPixel = 8;
inline constexpr int kRegatherLeastRays = 64;
inline constexpr int kRegatherMostRays = 4096;

// R = B - E per mesh position, Gouraud-interpolated by `fit` (VertexFit of the mesh): what a
// gather ray takes from the front side it meets (W/m^2 per band). INVALID_ARGUMENT when the
// sizes disagree.
absl::StatusOr<std::vector<Rgb>> ReflectedAtVertices(const PatchMesh& mesh, const VertexFit& fit,
                                                     const PatchAttributes& attributes,
                                                     const std::vector<Rgb>& patch_radiosity);

// The sum over traced `rays` of the reflected radiosity each meets: `at_vertex` (one value per
// mesh position, e.g. ReflectedAtVertices') interpolated where it meets a front side, at
// least 0; nothing for a miss or a back side. A gather's estimate of H is this over the count.
Rgb SumMetReflected(const PatchMesh& mesh, const std::vector<Rgb>& at_vertex,
                    std::span<const StreamRay> rays);

// Per patch, how many of `camera`'s pixel-centre rays meet its front side.
std::vector<uint32_t> PixelsPerPatch(const PatchMesh& mesh, const RayCaster& caster,
                                     const Camera& camera, int threads);

// I per patch (W/m^2 per band, >= 0): regathered as above for the patches `camera` shows,
// `patch_indirect` (the solve's) for the rest; R interpolated by `fit`. `caster` must report
// Embree's u,v; rays are seeded per patch from `seed`, so the values do not depend on `threads` (0
// = all cores). INVALID_ARGUMENT when the sizes disagree.
absl::StatusOr<std::vector<Rgb>> RegatherShownIndirect(
    const PatchMesh& mesh, const VertexFit& fit, const RayCaster& caster,
    const PatchAttributes& attributes, const std::vector<Rgb>& patch_radiosity,
    const std::vector<Rgb>& patch_indirect, const Camera& camera, uint64_t seed, int threads);

}  // namespace radflux
