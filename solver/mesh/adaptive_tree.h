// ElementTree: a subdivision hierarchy over the patches of a mesh (each patch a root;
// a quad splits into 4 quads at its edge midpoints and centre, a triangle into 4 at its
// edge midpoints). Used by adaptive meshing (leaves are the patches) and by hierarchical
// radiosity (every node is an element). Midpoints are computed as (a + b) / 2 from the
// two corner positions, so both sides of a shared edge produce bit-identical vertices;
// that is what lets BuildLeafMesh find T-junctions and close them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/sampling.h"
#include "solver/core/vec3.h"
#include "solver/mesh/patch_mesh.h"

namespace radflux {

inline constexpr uint32_t kNoElement = 0xffffffffu;

struct Element {
  std::array<Vec3, 4> corners;  // ccw seen from the front; corners[3] == corners[2] for a triangle
  bool triangle = false;
  bool two_sided = false;                // as Patch::two_sided
  float opacity = 1;                     // as Patch::opacity
  uint32_t face = 0;                     // source face in the Scene
  uint32_t parent = kNoElement;          // kNoElement for a root
  uint32_t first_child = kNoElement;     // 4 consecutive children, or kNoElement for a leaf
  uint32_t depth = 0;                    // 0 for a root
  Vec3 normal;                           // unit normal of the source face
  Vec3 centroid;                         // area-weighted centroid
  double area = 0;                       // scene units^2

  bool IsLeaf() const { return first_child == kNoElement; }
  int CornerCount() const { return triangle ? 3 : 4; }
};

struct ElementTree {
  std::vector<Element> nodes;   // roots first (in patch order), then children as split
  std::vector<uint32_t> roots;  // roots[k] = node of patch k

  // One root per patch of `mesh` (in patch order, so roots are grouped by face).
  static ElementTree FromMesh(const PatchMesh& mesh);

  // Splits leaf `node` into four children (appended); returns the first child's index.
  // Invalidates references into `nodes`.
  uint32_t Split(uint32_t node);

  // The leaves in depth-first order from the roots in root order (grouped by face).
  std::vector<uint32_t> Leaves() const;
};

// Uniform-by-area point on an element for u in [0,1)^2.
Vec3 SampleElementPoint(const Element& e, Point2 u);

// The element's corners as a polygon (3 or 4 points).
std::vector<Vec3> ElementPolygon(const Element& e);

// A PatchMesh with one patch per leaf in `leaves` (vertices shared within a face by exact
// position), or, when `conforming`, with every leaf that has neighbours' corners on its
// edges (T-junctions) replaced by a fan of triangles around its centroid that includes
// them, so the mesh has no T-junctions and per-vertex values have no seams.
// patch_leaf[p] = index into `leaves` of the leaf patch p came from; the patches of one
// leaf are consecutive and leaves appear in the order given (which must be grouped by face).
PatchMesh BuildLeafMesh(const ElementTree& tree, const std::vector<uint32_t>& leaves,
                        bool conforming, std::vector<uint32_t>* patch_leaf);

}  // namespace radflux
