// Coincident coplanar overlaps: two faces on the same plane covering part of each other (a
// classic export artefact; whichever a ray meets first hides the other, so light is blocked
// both ways). Found with a hash of planes and a 2D grid in each plane, not all pairs.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/scene/scene.h"

namespace radflux {

struct FaceOverlap {
  uint32_t a = 0, b = 0;  // face indices, a < b
};

// Pairs of faces in one plane (either facing) whose interiors overlap by more than 0.1% of
// the smaller face's area, in ascending (a, b) order. Faces must be planar and convex with
// non-zero area (as after the import rules); a face and its back-face twin (the same
// vertices reversed) are not an overlap. Faces in planes closer than ~1e-5 of the scene's
// size count as one plane.
std::vector<FaceOverlap> FindCoplanarOverlaps(const Scene& scene);

}  // namespace radflux
