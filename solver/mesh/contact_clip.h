// Cutting a face's patches along its contacts (contact_footprints.h): the parts of each patch
// outside every footprint stay, as convex triangles and quads whose edges follow the
// footprints' outlines and the contact lines; the parts inside a footprint are left out (the
// floor under a block is dark and hidden, so it needs no unknowns and must not darken the
// shading around it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/mesh/contact_footprints.h"
#include "solver/mesh/patch_mesh.h"

namespace radflux {

// Replaces the patches of the last face meshed into `mesh` (patches from `first_patch`,
// positions from `first_vertex`, all of one face with unit normal `normal`) by their parts
// outside `contacts.footprints` (polygons in the face's plane, counter-clockwise about
// `normal`), cut along `contacts.lines`:
// - for a footprint at least 3 patches across (area >= 9 reach^2, reach > 0: the face's
//   patch edge length, scene units), a patch within reach of it is first split in four by
//   its edges' midpoints, and the pieces within reach / 2 in four again (the light changes
//   fastest beside a contact: the floor there sees less of the room, and a block's shadow
//   starts at it), and patches near it (its bounding box grown by reach) are cut along the
//   lines of its sides, both sides kept (where a block's side starts or stops being seen);
// - a patch that reaches the contact line (its bounding box and the slab between its ends)
//   is cut along its line, both sides kept (so no patch straddles a partition's foot; the
//   cut may run on past the segment's end within a patch it crosses), and for a line at
//   least 3 patches long the patches within reach of it are split as beside a footprint;
// - the parts inside a footprint are left out;
// - the parts inside a slot (after the cuts above) are kept, as patches with Patch::hidden,
//   the parts outside as the other patches.
// A patch clear of all this keeps its corners, a quarter of one is a quad, and a piece a cut
// shaped becomes a fan of triangles (its refinement then splits into equal quarters); slivers
// under 1e-9 of their patch's area are dropped. Afterwards the face's positions are exactly the
// ones its patches use, shared between its patches when they are the same point (cuts and
// midpoints on a shared edge are computed the same way from both sides); a split patch's
// midpoint or a footprint's corner may sit on a neighbour's edge (a T-junction inside the
// face, which the shading mesh resolves like one between faces).
void ClipFacePatches(const FaceContacts& contacts, const Vec3& normal, double reach,
                     uint32_t first_patch, uint32_t first_vertex, PatchMesh& mesh);

// The number of patches ClipFacePatches would leave of the same face (same arguments), without
// building them: choosing the edge length for a target count meshes the cut faces many times.
size_t ClippedPatchCount(const FaceContacts& contacts, const Vec3& normal, double reach,
                         uint32_t first_patch, uint32_t first_vertex, const PatchMesh& mesh);

}  // namespace radflux
