// Baking radiance into a LightmapAtlas: each patch's triangles (quads split v0-v1-v3 and
// v2-v3-v1, as the render splits them) are rasterized into their face's chart at texel
// centres, with the per-vertex radiosity interpolated linearly (the render's Gouraud values),
// as radiance B / pi. Then each chart is dilated inside its own rectangle: gutter + 1 passes,
// each giving the uncovered texels next to covered ones the mean of their covered
// neighbours, so bilinear filtering at a chart's edge reads the chart's own values, never
// another chart's (the rectangles keep the gutter between them).
#pragma once

#include <vector>

#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/image.h"
#include "solver/output/lightmap_atlas.h"

namespace radflux {

// Radiance B / pi (W/m^2/sr per band) per texel of `atlas` (atlas.size squared; row 0 is the
// top, where glTF's v = 0 is), from `vertex_radiosity` (W/m^2 per band, one per
// mesh.positions); texels of no chart are 0.
Image BakeLightmap(const PatchMesh& mesh, const LightmapAtlas& atlas,
                   const std::vector<Rgb>& vertex_radiosity);

}  // namespace radflux
