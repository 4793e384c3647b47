// Per-patch values as CSV, for spreadsheets and for comparing two runs patch by patch.
// Header exactly `patch,face,object,area,cx,cy,cz,r,g,b`; one row per patch in patch
// order; area in scene units^2, centroid in scene units, r,g,b = radiosity B in W/m^2;
// numbers as %.9g. An object name with a comma or quote is quoted (RFC 4180).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/core/vec3.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

inline constexpr char kPatchValuesCsvHeader[] = "patch,face,object,area,cx,cy,cz,r,g,b";

// One row of the CSV.
struct PatchValue {
  uint32_t patch = 0;
  uint32_t face = 0;
  std::string object;  // the scene's object name of the patch's face
  double area = 0;     // scene units^2
  Vec3 centroid;       // scene units
  Rgb radiosity{};     // B, W/m^2 per band
};

// Writes one row per patch of `mesh` (built from `scene`) with `radiosity` (one per patch).
absl::Status WritePatchValuesCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                                 const std::vector<Rgb>& radiosity);

// Reads a file written by WritePatchValuesCsv; errors name the file and line.
absl::StatusOr<std::vector<PatchValue>> ReadPatchValuesCsv(const std::string& path);

}  // namespace radflux
