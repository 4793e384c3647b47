// The lit mesh as binary glTF 2.0 (.glb): one mesh of triangles over ShadingMesh's welded
// vertices (export_mesh.h: quads split along v1-v3 as Embree and the render split them,
// patches with T-junctions as fans around a centre) with POSITION, NORMAL, COLOR_0 and _RADIOSITY, and
// one KHR_materials_unlit material, so three.js and Blender show the baked colours as is.
// COLOR_0 is linear RGB in [0, 1] (the glTF rule): tone-mapped radiance B/pi without the
// sRGB curve, which viewers apply on display. _RADIOSITY is the raw B, W/m^2 per band.
// Units: glTF is in metres with +y up. Positions are written as scene coordinates times
// GltfOptions::metres_per_unit (0.001 for the Cornell box's millimetres); axes unchanged.
#pragma once

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/shading_mesh.h"
#include "solver/output/tone_map.h"

namespace radflux {

struct GltfOptions {
  double metres_per_unit = 1.0;  // scene unit in metres; positions are multiplied by it
  ToneMapOptions tone;           // its srgb flag is ignored: COLOR_0 is always linear
};

// Writes `mesh` lit by `patch_radiosity` (one Rgb per patch, W/m^2) to `path` as .glb.
// Fails, naming the file, for an empty mesh, a size mismatch or an I/O error.
absl::Status WriteGlb(const std::string& path, const PatchMesh& mesh, const ShadingMesh& shading,
                      const std::vector<Rgb>& patch_radiosity, const GltfOptions& options);

}  // namespace radflux
