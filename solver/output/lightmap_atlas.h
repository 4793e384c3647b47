// LightmapAtlas: a second UV set for a PatchMesh, one chart per source face. A chart is the
// face laid flat in its own plane (Frame::FromNormal of its normal, so no distortion), at
// one texel density for the whole scene, inside a rectangle of texels that keeps `gutter`
// empty texels on every side; the rectangles are packed on shelves (tallest first) into a
// square of `size` texels and never overlap, so two charts are always at least 2 * gutter
// texels apart. The density is the largest (to 1%) at which every rectangle fits.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/sampling.h"
#include "solver/core/vec3.h"
#include "solver/mesh/patch_mesh.h"

namespace radflux {

struct LightmapChart {
  uint32_t face = 0;          // source face (Patch::face)
  Frame frame;                // the face's plane: s, t in it, n its normal
  double s0 = 0, t0 = 0;      // the face's lowest (s, t), scene units
  int x = 0, y = 0;           // the rectangle's corner, texels (x right, y down the image)
  int width = 0, height = 0;  // the rectangle, texels, gutters included
};

struct LightmapAtlas {
  int size = 0;                // the square texture's side, texels
  int gutter = 0;              // empty texels kept around each chart inside its rectangle
  double texels_per_unit = 0;  // texels per scene unit
  std::vector<LightmapChart> charts;
  std::vector<uint32_t> chart_of_face;  // per face index: its chart

  // Texel coordinates (continuous; texel (i, j) covers [i, i+1) x [j, j+1)) of point p on
  // the chart's face.
  Point2 Texel(const LightmapChart& chart, const Vec3& p) const;
  // The same as glTF UVs in [0, 1] (u right, v down: glTF's image convention).
  Point2 Uv(const LightmapChart& chart, const Vec3& p) const;
};

// Charts for the faces of `mesh`, packed into size x size texels with `gutter` (>= 2).
// INVALID_ARGUMENT when size is outside [16, 16384], gutter < 2, the mesh is empty, or the
// charts cannot fit even at one texel per chart's longest side.
absl::StatusOr<LightmapAtlas> BuildLightmapAtlas(const PatchMesh& mesh, int size, int gutter = 2);

}  // namespace radflux
