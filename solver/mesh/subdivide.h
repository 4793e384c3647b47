// Uniform subdivision of a validated scene into patches. The mesh depends only on the
// scene and the options, so runs with the same --patches compare patch by patch.
#pragma once

#include <cstdint>
#include <span>
#include <utility>

#include "absl/status/statusor.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

// An emitting face is split into at most this many steps along each edge (see
// FaceEdgeLength in subdivide.cc): its B is almost all its own E.
inline constexpr int kMaxEmitterSteps = 8;

struct MeshOptions {
  int64_t target_patches = 0;   // aim for this many patches in the scene (closest count wins)
  double max_edge = 0;          // or: no patch edge longer than this (scene units)
  bool group_faces = true;      // SubdivideAndGroup: when the faces reach target_patches, the
                                // unknowns are groups of patches (face_grouping.h)
  bool follow_contacts = true;  // cut faces along the feet of solids resting on them (below)
  double min_contact_area = 0;  // ... on faces of at least this area only (scene units^2)
  // Neither set: every face becomes one patch (quads and triangles) or a fan.
};

// The scene's face area (scene units^2), each face once.
double TotalFaceArea(const Scene& scene);

// Subdivides every face: triangles into n^2 triangles, quads into a nu x nv grid,
// larger convex polygons into a fan of subdivided triangles around their centroid. Where a
// closed solid rests on a face (contact_footprints.h), the face's patches are cut along the
// solid's outline and the part under it is left out, and along the foot of a face standing on
// it that closes no such loop (a partition) (contact_clip.h): with follow_contacts, on the
// faces of at least min_contact_area, and with at least as many faces as target_patches (one
// patch a face) only on faces of total area / target_patches or more. A scene of more faces
// than the target has its unknowns made of groups of faces (face_grouping.h); it is split
// with a max_edge and the contacts of its large faces only (a wall's part behind a board must
// not share an unknown with its lit part; finding every small face's contacts costs far more
// than meshing).
// With `least_steps` (one (nu, nv) per face, or empty), a quad face is split into at least
// that many steps each way (formfactor/near_field_steps.h: strips across a lamp's near field),
// counted in target_patches.
absl::StatusOr<PatchMesh> SubdivideScene(const Scene& scene, const MeshOptions& options,
                                         std::span<const std::pair<int, int>> least_steps = {});

struct MeshStats {
  size_t patches = 0;
  double min_area = 0, max_area = 0;
  double max_aspect = 0;  // longest edge^2 / area, 1 for a square or equilateral triangle
};
MeshStats ComputeMeshStats(const PatchMesh& mesh);

}  // namespace radflux
