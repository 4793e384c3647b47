// Uniform subdivision of a validated scene into patches. The mesh depends only on the
// scene and the options, so runs with the same --patches compare patch by patch.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

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

// Lines a quad face must be cut along whatever the edge length: parameters in (0, 1),
// ascending, along u (vertices 0 -> 1) and v (0 -> 3).
struct QuadCuts {
  std::vector<double> u, v;
};
// The faces that have such lines (few: those near emitters), by face index.
using QuadCutsByFace = std::unordered_map<uint32_t, QuadCuts>;

// The scene's face area (scene units^2), each face once.
double TotalFaceArea(const Scene& scene);

// Subdivides every face: triangles into n^2 triangles, quads into a nu x nv grid,
// larger convex polygons into a fan of subdivided triangles around their centroid. Where a
// closed solid rests on a face (contact_footprints.h), the face's patches are cut along the
// solid's outline and the part under it is left out, and along the foot of a face standing on
// it that closes no such loop (a partition) (contact_clip.h); a quad side of such a solid gets
// a first row a third of its patch edge high along its foot (subdivide.cc, kFootStrip): with
// follow_contacts, on the
// faces of at least min_contact_area, and with at least as many faces as target_patches (one
// patch a face) only on faces of total area / target_patches or more. A scene of more faces
// than the target has its unknowns made of groups of faces (face_grouping.h); it is split
// with a max_edge and the contacts of its large faces only (a wall's part behind a board must
// not share an unknown with its lit part; finding every small face's contacts costs far more
// than meshing).
// A quad listed in `cuts` is also cut along its lines (formfactor/near_field_cuts.h: strips
// across a lamp's near field, and its lamp's outline), each interval between them split as the
// edge length asks; they count in target_patches.
absl::StatusOr<PatchMesh> SubdivideScene(const Scene& scene, const MeshOptions& options,
                                         const QuadCutsByFace& cuts = {});

struct MeshStats {
  size_t patches = 0;
  double min_area = 0, max_area = 0;
  double max_aspect = 0;  // longest edge^2 / area, 1 for a square or equilateral triangle
};
MeshStats ComputeMeshStats(const PatchMesh& mesh);

}  // namespace radflux
