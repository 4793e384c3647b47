// Render: a picture of the radiosity solution through a pinhole camera. Each primary ray
// takes the radiance B/pi (W/m^2/sr) interpolated from per-vertex radiosity at its
// nearest hit (barycentric on triangles, bilinear on quads); rays that escape or hit a patch from
// behind give black.
#pragma once

#include <array>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/camera.h"
#include "solver/output/image.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

struct RenderOptions {
  int samples_per_axis = 1;  // n x n stratified (fixed, not random) samples per pixel
  int threads = 0;           // 0 = all cores; the image does not depend on it
};

// Interpolation weights of vertices v[0..3] of patch `p` at Embree's hit coordinates
// (u, v). A triangle (v3 == v2) gets its barycentrics (1-u-v, u, v, 0). A quad gets
// bilinear weights (1-s)(1-t), s(1-t), st, (1-s)t in its own parameters (s, t), found by
// inverting the bilinear map at the hit point (Embree splits a quad into triangles
// (v0,v1,v3) and (v2,v3,v1), reporting u,v in the second as 1-u', 1-v'): values vary
// linearly along every edge, as on the neighbour across it, with no streak along a
// diagonal, and a linear function is reproduced exactly on any planar convex quad. On a
// parallelogram (s, t) = (u, v) and no inversion is needed.
// The weights sum to 1.
std::array<double, 4> PatchVertexWeights(const PatchMesh& mesh, uint32_t p, double u, double v);

// Radiosity (W/m^2 per band) at `hit` from per-vertex values; `hit` must hit a patch.
Rgb InterpolateAtHit(const PatchMesh& mesh, const std::vector<Rgb>& vertex_values, const Hit& hit);

// Radiance image of `vertex_radiosity` (one Rgb per mesh vertex, W/m^2) seen by `camera`,
// with rays cast by `caster`, which must report Embree's u,v (EmbreeRayCaster does).
absl::StatusOr<Image> RenderRadiance(const PatchMesh& mesh, const RayCaster& caster,
                                     const std::vector<Rgb>& vertex_radiosity, const Camera& camera,
                                     const RenderOptions& options);

}  // namespace radflux
