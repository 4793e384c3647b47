// Contact footprints and lines (the classic D0 discontinuities): where a closed solid rests on
// a face, e.g. a block on the floor, the region of the face under it gets no light and its
// outline is a discontinuity of the light; where a face stands on it without closing a loop,
// e.g. a partition or a panel, the light on the two sides of its foot differs. The mesher
// cuts patches along the outlines and lines and leaves the footprints out (contact_clip.h),
// so no patch straddles light and dark.
#pragma once

#include <vector>

#include "solver/core/vec3.h"
#include "solver/scene/scene.h"

namespace radflux {

// One footprint on a receiving face: a simple polygon in the face's plane, counter-clockwise
// seen from the face's front, which may extend beyond the face.
using Footprint = std::vector<Vec3>;

// An open contact line on a receiving face: an edge a-b of a face standing on it, in its plane.
struct ContactSegment {
  Vec3 a, b;
};

// The contacts of one receiving face.
struct FaceContacts {
  std::vector<Footprint> footprints;  // feet of solids: cut along and left out
  std::vector<ContactSegment> lines;  // the other contact edges: cut along, both sides kept
  std::vector<Footprint> slots;       // under an emitter facing the face: cut along, kept,
                                      // hidden from view (Patch::hidden)
  std::vector<int> feet;  // this face's own edges (i -> i + 1) that are a footprint's, the
                          // face a side of a solid resting on a receiver: the mesher cuts a
                          // strip along them (subdivide.h). A partition's or a wall's foot is
                          // no foot here: strips along office2's walls made its floor noisy.
  // No cuts into this face (its feet cut only a strip of its own grid).
  bool empty() const { return footprints.empty() && lines.empty() && slots.empty(); }
};

// Contacts per scene face (most empty). A contact edge is an edge of another face lying in
// the receiver's plane (within 1e-5 of the scene's bounding-box diagonal), where that face
// stands on the receiver's front side (no corner behind it), is not parallel to it, and the
// edge does not lie along the receiver's border (a neighbouring face of a tessellated surface
// meets it there; it does not stand on it). A footprint is a closed loop of contact edges
// where:
// - every face of the loop has its normal pointing out of the loop (the loop is the foot of a
//   solid, not a room's walls around an inner floor, whose normals point in);
// - the loop's faces are of one object, and a face of that object facing away from the
//   receiver lies above the loop's centroid (a lid: an open tube's inside stays lit).
// A face lying in front of the receiver with its back to it (facing the same way, every
// corner in front by more than that tolerance and at most 2% of the face's size, the square
// root of its area, or of the smaller one's when the receiver emits) also gives a footprint:
// its outline projected onto the receiver (a light hung 0.5 mm below a ceiling hides the
// ceiling above it; without the cut, the ceiling's patches under its edge averaged the dark
// and the lit parts and shaded the lit part dark; a lamp's top 2 cm below a two-sided
// ceiling is not hidden by the ceiling's back).
// A face that is two-sided (its material's; it has a back-to-back twin) and does not emit
// keeps that part instead, as a slot's hidden patches (below): left out, it would be a hole,
// since the ray casters see through its twin's back. RenderPark's classroom's lamp housings
// are double shells 2 mm apart under the ceiling's two-sided tiles, each hiding the other's
// inner side and the ceiling's outward twin hiding their tops: the holes let the tubes' light
// through to the ceiling, whose patches over the housings shone 5 times too bright (energy
// balance 45% off at 8,000 patches).
// An emitting face facing the receiver, every corner in front by more
// than the tolerance and at most its width (twice its area over its longest edge) and 2% of
// the receiver's size, gives a slot instead: the receiver's part under it is a narrow cavity
// that the emitter lights far more than the rest (the conference room's screen, 1.5 units
// behind the emitting bars of its frame, read B/pi 48 there against 20.6 beside them), seen
// from the room only through the slits along its sides; it is cut along and kept, so that
// its light is exchanged and leaks out as it does, but its patches are hidden from the
// shading of their visible neighbours.
// Every other contact edge (a partition's foot, an open polyline of panels, a loop that is no
// foot) is a line, once however many faces share it, and none along a footprint's edge.
// Only faces of at least `min_receiver_area` (scene units^2) are receivers; the others get no
// contacts (a scene of many small faces needs the contacts of its large ones only, and finding
// every face's costs far more). Edges are found through a uniform grid of face bounding boxes,
// not all pairs.
std::vector<FaceContacts> FindContacts(const Scene& scene, double min_receiver_area = 0);

}  // namespace radflux
