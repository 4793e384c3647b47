// The lit mesh as binary little-endian PLY: per vertex the position (scene units), the
// unit normal, the radiosity as floats (W/m^2 per band: radiosity_r/_g/_b) and 8-bit
// colours red/green/blue tone mapped from radiance B/pi exactly as the PNG is. The
// vertices are ShadingMesh's welded ones; per patch one face, counter-clockwise seen from
// the lit side: its 3 or 4 corners plus the T-junction vertices on its edges.
#pragma once

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/shading_mesh.h"
#include "solver/output/tone_map.h"

namespace radflux {

// Writes `mesh` with per-vertex values derived from `patch_radiosity` (one Rgb per patch,
// W/m^2) to `path`. Fails, naming the file, on size mismatch or I/O error.
absl::Status WritePly(const std::string& path, const PatchMesh& mesh, const ShadingMesh& shading,
                      const std::vector<Rgb>& patch_radiosity, const ToneMapOptions& tone);

}  // namespace radflux
