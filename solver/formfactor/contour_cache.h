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

#include "solver/mesh/patch_mesh.h"

namespace radflux {

// The distinct edges of a mesh's patches: edge k of patch p runs from its vertex k to
// vertex k + 1 (mod its vertex count); two patch edges are one edge when they join the
// same two vertex indices.
class PatchEdges {
 public:
  explicit PatchEdges(const PatchMesh& mesh);
  size_t size() const { return count_; }
  // The edge of patch p's edge k, and whether the patch runs it against the edge's own
  // direction (from its higher vertex index to its lower).
  uint32_t Id(uint32_t p, int k) const { return id_[4 * p + static_cast<uint32_t>(k)] >> 1; }
  bool Reversed(uint32_t p, int k) const { return id_[4 * p + static_cast<uint32_t>(k)] & 1; }

 private:
  std::vector<uint32_t> id_;  // 4 per patch: edge id << 1 | reversed
  size_t count_ = 0;
};

// One thread's cache for one row at a time.
class ContourCache {
 public:
  // Starts a row: its sample points (all on one plane) and the plane's unit normal.
  void Begin(const PatchMesh& mesh, const PatchEdges& edges, std::span<const Vec3> points,
             const Vec3& normal);
  // UnclippedPointToPolygonFormFactor(points[m], normal, patch j's vertices), bit for bit.
  double FormFactor(uint32_t j, size_t m);

 private:
  const PatchMesh* mesh_ = nullptr;
  const PatchEdges* edges_ = nullptr;
  std::span<const Vec3> points_;
  Vec3 normal_;
  std::vector<double> term_;     // [edge * points + m]: the term in the edge's direction
  std::vector<uint64_t> stamp_;  // [edge * points + m]: the row whose term term_ holds
  uint64_t row_ = 0;             // rows begun so far (stamps are never reused)
};

}  // namespace radflux
