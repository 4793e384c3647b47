// DefaultView: where the camera goes when the user gives no --camera-pos, chosen by one
// stated rule so that the default picture shows the scene, from inside for an interior.
//
// Probe points on a 6x6x6 grid in the bounding box cast 64 rays each; a point is inside
// when at most a quarter of its rays escape or hit the back of a one-sided patch and at
// least half of them meet a lit patch (B > 0: not the dark inside of a closed solid, such
// as a two-sided sphere, or of a luminaire's housing). Up is the caller's, else +y or +z
// (OBJ's and glTF's convention, or a z-up model such as an MGF file), whichever more patch
// area faces along (floors, ceilings, table tops).
// A point inside: the one with the largest mean free distance marks the largest open
// volume: the camera goes to 55% of the floor-to-ceiling height there and casts 16
// horizontal rays. If 3 or more escape (a box open at one side, like the Cornell box; a
// window or a door lets fewer through), it looks in through that opening from outside
// along the nearest box axis, the opening filling the picture. Otherwise it looks along the
// volume's longest horizontal axis (the principal axis of the 16 hit points, snapped to a
// box axis within 10 degrees) towards the farther end, from 90% of the way to the wall
// behind.
// No point inside (an open scene: a floor with objects on it, a lone luminaire): the camera
// looks at the box's centre from outside, from one of 24 directions: 8 azimuths around up
// (the first along +z, or +y when z is up) at elevations +30 (from above), 0 and -30
// degrees, each at the distance that just fits the box's 8 corners in the picture; the
// first of them whose 32-pixel-wide probe picture has the most pixels on a lit patch.
#pragma once

#include <span>

#include "solver/core/bands.h"
#include "solver/core/vec3.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/camera.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

// The default view of `mesh` (non-empty) for a picture of `camera`'s size and field of
// view, lit by `radiosity` (B per patch, mesh.size() of them). `up`: the caller's up
// vector, or zero to let the rule pick it. The result's
// position, look-at and up are set; the camera is valid (ValidateCamera).
Camera DefaultCamera(const PatchMesh& mesh, const RayCaster& caster, std::span<const Rgb> radiosity,
                     const Camera& camera, const Vec3& up);

// The rule's up: +y or +z (see above).
Vec3 SceneUpAxis(const PatchMesh& mesh);

}  // namespace radflux
