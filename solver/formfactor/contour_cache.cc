#include "solver/formfactor/contour_cache.h"

#include <algorithm>
#include <tuple>

#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {

PatchEdges::PatchEdges(const PatchMesh& mesh) : id_(4 * mesh.size(), 0) {
  // (lower vertex, higher vertex, slot 4p + k), sorted so that equal edges are adjacent.
  std::vector<std::tuple<uint32_t, uint32_t, uint32_t>> ends;
  ends.reserve(4 * mesh.size());
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    const int count = patch.VertexCount();
    for (int k = 0; k < count; ++k) {
      const uint32_t a = patch.v[static_cast<size_t>(k)];
      const uint32_t b = patch.v[static_cast<size_t>((k + 1) % count)];
      ends.emplace_back(std::min(a, b), std::max(a, b),
                        (4 * p + static_cast<uint32_t>(k)) << 1 | (a > b));
    }
  }
  std::sort(ends.begin(), ends.end());
  for (size_t e = 0; e < ends.size(); ++e) {
    const auto [lo, hi, slot] = ends[e];
    if (e > 0 && (lo != std::get<0>(ends[e - 1]) || hi != std::get<1>(ends[e - 1]))) ++count_;
    id_[slot >> 1] = static_cast<uint32_t>(count_) << 1 | (slot & 1);
  }
  if (!ends.empty()) ++count_;
}

void ContourCache::Begin(const PatchMesh& mesh, const PatchEdges& edges,
                         std::span<const Vec3> points, const Vec3& normal) {
  mesh_ = &mesh;
  edges_ = &edges;
  points_ = points;
  normal_ = normal;
  const size_t entries = edges.size() * points.size();
  if (term_.size() < entries) {
    term_.resize(entries);
    stamp_.resize(entries, 0);
  }
  ++row_;
}

double ContourCache::FormFactor(uint32_t j, size_t m) {
  const Patch& patch = mesh_->patches[j];
  const int count = patch.VertexCount();
  const Vec3& x = points_[m];
  double sum = 0;
  for (int k = 0; k < count; ++k) {
    const size_t entry = edges_->Id(j, k) * points_.size() + m;
    const bool reversed = edges_->Reversed(j, k);
    if (stamp_[entry] != row_) {
      // The term in the edge's own direction (lower vertex index to higher).
      const uint32_t a = patch.v[static_cast<size_t>(k)];
      const uint32_t b = patch.v[static_cast<size_t>((k + 1) % count)];
      const Vec3& from = mesh_->positions[reversed ? b : a];
      const Vec3& to = mesh_->positions[reversed ? a : b];
      term_[entry] = ContourEdgeTerm(from - x, to - x, normal_);
      stamp_[entry] = row_;
    }
    sum += reversed ? -term_[entry] : term_[entry];
  }
  return FormFactorFromContourSum(sum);
}

}  // namespace radflux
