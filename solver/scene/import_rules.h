// The import rules of issue 19, applied to every scene whatever its format (LoadScene calls
// this after any loader), so that a user's scene goes in as it comes with every change to
// it said once. In order:
//   1. materials: --emit makes emitters, --two-sided marks every material two-sided,
//      reflectance >= 1 in a band is clamped to --max-reflectance;
//   2. the scene is recentred in double when it lies far from the origin (recentre.h);
//   3. faces: repeated consecutive vertices removed, zero-area faces dropped, non-planar
//      faces split into triangles (quads along the shorter diagonal), non-convex planar
//      faces triangulated by ear clipping in their plane;
//   4. duplicate faces dropped (duplicate_faces.h);
//   5. two-sided faces get their back-face twin (two_sided.h);
//   6. coplanar overlaps are found and reported, not changed (coplanar_overlaps.h).
// Each kind of change is one entry of scene.import_log (count and first file:line).
#pragma once

#include "absl/status/status.h"
#include "solver/scene/import_options.h"
#include "solver/scene/scene.h"

namespace radflux {

// Applies the rules to `scene` in place. With options.strict nothing is fixed: the first
// material or face a rule would change is refused with ValidateScene's message (file:line
// and what is wrong; a duplicate names the face it repeats). INVALID_ARGUMENT also for an
// --emit naming no material of the scene, or a max_reflectance outside (0, 1).
absl::Status ApplyImportRules(const ImportOptions& options, Scene& scene);

}  // namespace radflux
