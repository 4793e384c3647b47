// PatchMesh: the scene's faces split into patches, the unknowns of the radiosity
// system. A patch is a planar convex triangle or quad that remembers its source face.
// Patches of one face share vertices (no T-junctions inside a face, except where contact
// meshing cut or split them: contact_clip.h); faces never share vertices, so per-vertex
// values keep creases between faces sharp.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/sampling.h"
#include "solver/core/vec3.h"

namespace radflux {

struct Patch {
  std::array<uint32_t, 4> v{};  // PatchMesh::positions indices, ccw; v[3] == v[2] for a triangle
  uint32_t face = 0;            // source face in the Scene
  bool two_sided = false;       // its face has a back-face twin: hits on its back are ignored
  float opacity = 1;            // its material's Material::opacity: rays pass with 1 - opacity
  bool hidden = false;          // in a slot under an emitter facing it (contact_footprints.h):
                                // an unknown of its own, kept out of its visible neighbours'
                                // shading (vertex_radiosity.h)
  Vec3 centroid;                // area-weighted centroid
  Vec3 normal;                  // unit normal of the source face (front side)
  double area = 0;              // scene units^2

  bool IsTriangle() const { return v[2] == v[3]; }
  int VertexCount() const { return IsTriangle() ? 3 : 4; }
};

struct PatchMesh {
  std::vector<Vec3> positions;
  std::vector<Patch> patches;
  std::vector<uint32_t> face_first_patch;   // patches of face f: [first[f], first[f+1])
  std::vector<uint32_t> face_first_vertex;  // vertices of face f: [first[f], first[f+1])

  size_t size() const { return patches.size(); }
  Vec3 Vertex(uint32_t patch, int k) const { return positions[patches[patch].v[k]]; }
};

// Uniform-by-area points on one patch, with its corners and split precomputed so that a
// sample costs a few multiply-adds and no branch (inline: the builders call it per ray).
// Stratification of u is kept.
class PatchPointSampler {
 public:
  PatchPointSampler(const PatchMesh& mesh, uint32_t p);
  Vec3 operator()(Point2 u) const {
    // u.x < first_ picks triangle (a, b, c), else (a, c, d); u.x is rescaled to [0, 1).
    const bool first = u.x < first_;
    const Vec3& b = first ? b_ : c_;
    const Vec3& c = first ? c_ : d_;
    const double x = std::min(Select(first, u.x, u.x - first_) / Select(first, first_, 1 - first_),
                              0x1.fffffffffffffp-1);
    const auto [b0, b1] = SampleUniformTriangle({x, u.y});
    return a_ * b0 + b * b1 + c * (1 - b0 - b1);
  }

 private:
  Vec3 a_, b_, c_, d_;
  double first_;  // area fraction of triangle (a, b, c); 1 for a triangle patch
};

// `mesh` moved by `offset` (positions and centroids; areas and normals unchanged): how
// outputs put a recentred scene's mesh back in the file's coordinates (Scene::origin).
PatchMesh TranslatedMesh(const PatchMesh& mesh, const Vec3& offset);

// Fills area, centroid and normal of `patch` from its vertices and face normal.
void FinishPatch(const std::vector<Vec3>& positions, const Vec3& face_normal, Patch& patch);

}  // namespace radflux
