// Contact footprints (the classic D0 discontinuities): where a closed solid rests on a face,
// e.g. a block on the floor, the region of the face under it gets no light and its outline
// is a discontinuity of the light. The mesher cuts patches along the outline and leaves the
// region out (contact_clip.h), so no patch straddles light and dark.
#pragma once

#include <vector>

#include "solver/core/vec3.h"
#include "solver/scene/scene.h"

namespace radflux {

// One footprint on a receiving face: a simple polygon in the face's plane, counter-clockwise
// seen from the face's front, which may extend beyond the face.
using Footprint = std::vector<Vec3>;

// Footprints per scene face (one list per face, most empty). A footprint is a closed loop of
// other faces' edges lying in the receiver's plane (within 1e-5 of the scene's bounding-box
// diagonal), where:
// - no edge of the loop lies along the receiver's border (a neighbouring face of a
//   tessellated surface meets it there; it does not stand on it);
// - every face of the loop stands on the receiver's front side, is not parallel to it, and
//   has its normal pointing out of the loop (the loop is the foot of a solid, not a room's
//   walls around an inner floor, whose normals point in);
// - the loop's faces are of one object, and a face of that object facing away from the
//   receiver lies above the loop's centroid (a lid: an open tube's inside stays lit).
// A face lying in front of the receiver with its back to it (facing the same way, every
// corner in front by more than that tolerance and at most 1% of the face's size, the square
// root of its area) also gives a footprint: its outline projected onto the receiver (a light
// hung 0.5 mm below a ceiling hides the ceiling above it; without the cut, the ceiling's
// patches under its edge averaged the dark and the lit parts and shaded the lit part dark).
// Edges are found through a uniform grid of face bounding boxes, not all pairs.
std::vector<std::vector<Footprint>> FindContactFootprints(const Scene& scene);

}  // namespace radflux
