// ShadingMesh: the connectivity that smooth shading needs on top of a PatchMesh, whose
// faces never share vertices. Vertices of different faces are welded when they lie at
// the same point (within a tolerance relative to the scene's size), belong to faces of
// the same material, and the faces' normals are within a crease angle; a welded vertex
// that lies inside another patch's edge on the same smooth surface is a T-junction of
// that patch. Per-vertex values (vertex_radiosity.h) are computed per welded vertex, so
// Gouraud shading is continuous across face edges, and writers emit the welded mesh with
// T-junction vertices inserted into the patches' outlines, so viewers do not crack.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/vec3.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

struct ShadingOptions {
  double crease_degrees = 30;    // faces meeting at a larger angle keep a sharp crease
  double weld_tolerance = 1e-6;  // fraction of the bounding box diagonal
};

// A welded vertex that lies strictly inside edge `edge` (v[edge] -> v[edge + 1]) of `patch`.
struct TJunction {
  uint32_t vertex = 0;  // welded vertex id
  uint32_t patch = 0;
  int edge = 0;
  double t = 0;  // position along the edge, in (0, 1)
};

struct ShadingMesh {
  std::vector<uint32_t> welded;          // per PatchMesh position: its welded vertex id
  std::vector<uint32_t> representative;  // per welded vertex: one PatchMesh position of it
  std::vector<Vec3> normals;             // per welded vertex: unit area-weighted mean normal
  std::vector<uint32_t> first_patch;     // patches using welded vertex w:
  std::vector<uint32_t> vertex_patches;  //   vertex_patches[first_patch[w] .. first_patch[w+1])
  std::vector<TJunction> t_junctions;    // ordered by (patch, edge, t)

  size_t size() const { return representative.size(); }
};

// Material of each scene face, the key welding compares (faces of different materials
// never share a shading vertex).
std::vector<uint32_t> FaceMaterials(const Scene& scene);

// Welds `mesh` and finds its T-junctions. `face_material` has one entry per scene face
// that the patches name. Fails on a size mismatch or bad options.
absl::StatusOr<ShadingMesh> BuildShadingMesh(const PatchMesh& mesh,
                                             const std::vector<uint32_t>& face_material,
                                             const ShadingOptions& options = {});

// The outline of patch `p` in welded vertex ids, ccw: its corners with the T-junction
// vertices of each edge inserted in order along the edge.
std::vector<uint32_t> PatchOutline(const PatchMesh& mesh, const ShadingMesh& shading, uint32_t p);

}  // namespace radflux
