// ContourCache: Lambert's contour terms of a mesh's patch edges, seen from the sample points
// of one row, each computed once and shared by the patches on either side of the edge.
// Adjacent patches of a face share an edge with opposite orientations, whose terms are
// exactly opposite (ContourEdgeTerm), so the analytic builder pays for about half the
// atan2 of a row and every form factor stays bit for bit what
// UnclippedPointToPolygonFormFactor gives.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/formfactor/pair_patches.h"
#include "solver/mesh/patch_mesh.h"

namespace radflux {

// The distinct edges of a mesh's patches: edge k of patch p runs from its vertex k to
// vertex k + 1 (mod its vertex count); two patch edges are one edge when they join the
// same two vertex indices.
class PatchEdges {
 public:
  explicit PatchEdges(const PatchMesh& mesh);
  size_t size() const { return count_; }
  // The edge of patch p's edge k (in [0, size())) << 1, | 1 when the patch runs it against
  // the edge's own direction (from its higher vertex index to its lower).
  uint32_t Slot(uint32_t p, uint32_t k) const { return id_[4 * p + k]; }

 private:
  std::vector<uint32_t> id_;  // 4 per patch: edge id << 1 | reversed
  size_t count_ = 0;
};

// One thread's cache for one row at a time.
class ContourCache {
 public:
  // Starts a row: its sample points (all on one plane) and the plane's unit normal, with
  // the patches and edges of one mesh.
  void Begin(const PairPatches& patches, const PatchEdges& edges, std::span<const Vec3> points,
             const Vec3& normal);
  // UnclippedPointToPolygonFormFactor(points[m], normal, patch j's vertices), bit for bit.
  double FormFactor(uint32_t j, size_t m);

 private:
  struct Term {
    double value = 0;  // the term in the edge's own direction
    uint64_t row = 0;  // the row whose term `value` is
  };
  const PairPatches* patches_ = nullptr;
  const PatchEdges* edges_ = nullptr;
  std::span<const Vec3> points_;
  Vec3 normal_;
  std::vector<Term> term_;  // [edge * points + m]
  uint64_t row_ = 0;        // rows begun so far (a term's row is never reused)
};

}  // namespace radflux
