// Near-field cuts: the lines a quad face close to an emitter must be cut along so that no
// patch averages very different direct light. A lamp housing's inside 2 cm from its tube sees a
// peaked irradiance across its width (7 times brighter above the tube than 4 cm aside) and a
// flat one along it; one patch across that width gives the tube back the width's mean, not
// the bright strip above it, and sends the strip's light into the room instead (RenderPark's
// classroom: its fixtures let out 72% of their light at the default mesh, 68.2% converged and
// by particle tracing; its lamps read 3% dark). The steps follow the unoccluded irradiance
// itself (Lambert's point-to-polygon form factor from the emitters near the face), per
// direction: a housing is cut into strips along its tube, not into squares. And a face is cut
// where its emitters' outlines lie over it: the housing's 5 cm beyond each end of its tube,
// half as bright, averaged into one patch with the part over the tube, took 5% of the light
// the tube gets back (the classroom's lamps 1.2% dark; cut there, 0.6%).
#pragma once

#include "absl/status/statusor.h"
#include "solver/mesh/subdivide.h"
#include "solver/scene/scene.h"

namespace radflux {

// Steps along a line are chosen to minimise the miss of equal steps showing their means (the
// mean absolute deviation from the unoccluded form factor to the emitters near the face, as a
// share of its mean along the line) plus this much per step.
inline constexpr double kNearFieldStepCost = 0.02;
// Faces whose peak form factor to nearby emitters is below this are left alone: the light of
// an emitter that far (against the face's size) varies smoothly, and the probe's cells take it.
inline constexpr double kNearFieldMinPeak = 0.1;
// ... and so are faces that reflect less than this share of the scene's emitted power from the
// near emitters' direct light (rho D A, D their unoccluded irradiance averaged over the
// samples): a block face beside one of Lost Empire's 900 torches matters to no one, while a
// classroom housing's top sends ~1% of the room's light back to its tube.
inline constexpr double kNearFieldMinPower = 1e-3;
// At most this many steps along each side from the near field, and at most this many
// outline lines each way (more emitters over a face than that: its equal steps alone).
inline constexpr int kMaxNearFieldSteps = 16;
// An outline closer than this (a share of the side) to the face's edge is no line of its own.
inline constexpr double kOutlineMargin = 0.01;

// The faces of `scene` that need cutting by the rule above, with their lines (u along
// vertices 0 -> 1, v along 0 -> 3, as subdivide.h's quads): per direction the equal steps
// the rule picks or, where it picks one step, the extent (least and greatest parameter) of
// each emitter that lights the face, projected on the face's plane, where it falls inside.
// Emitters, faces that are not quads, and faces no emitter is near (an emitter is near when
// its bounding box lies within the face's longest edge of the face's box) are not listed.
// Samples the form factor on 33 points along three lines each way; an emitter counts at a
// point only when no face of the scene blocks the segment to its centroid (traced by Embree on
// the scene's faces, built only when some face could need cuts). Errors are Embree's.
absl::StatusOr<QuadCutsByFace> NearFieldCuts(const Scene& scene);

}  // namespace radflux
