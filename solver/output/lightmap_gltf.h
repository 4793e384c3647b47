// The lit scene as binary glTF 2.0 with a lightmap (--out scene.glb --lightmap SIZE): the
// patches as triangles (quads split v0-v1-v3 and v2-v3-v1) over PatchMesh's positions, which
// faces never share, with POSITION, NORMAL, TEXCOORD_0 (the face laid flat, metres) and
// TEXCOORD_1 (its chart in the LightmapAtlas), and one material that shows the baked
// radiosity as emission: baseColor black, emissiveTexture on TEXCOORD_1, emissiveFactor 1.
// HDR route: KHR_materials_emissive_strength plus an 8-bit sRGB PNG (embedded): a texel's
// decoded linear value times emissiveStrength S is the tone-mapped radiance
// tone.scale * 2^stops * B / pi (the vertex-coloured GLB's scale, unclamped), S being the
// largest such value (at least 1), so the lamp keeps its brightness above 1. The material's
// extras hold "radflux_radiance_scale" = tone.scale * 2^stops, so B = pi * S * decoded / scale.
// Units and axes as WriteGlb (gltf_writer.h).
#pragma once

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/gltf_writer.h"
#include "solver/output/shading_mesh.h"

namespace radflux {

// Writes `mesh` lit by `patch_radiosity` (W/m^2 per patch), its radiosity interpolated over
// `shading`'s welded vertices (VertexRadiosity) and baked into a size x size lightmap with a
// 2-texel gutter, to `path`. Fails, naming the file, on bad sizes or an I/O error.
absl::Status WriteLightmapGlb(const std::string& path, const PatchMesh& mesh,
                              const ShadingMesh& shading, const std::vector<Rgb>& patch_radiosity,
                              int size, const GltfOptions& options);

}  // namespace radflux
