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

void ContourCache::Begin(const PairPatches& patches, const PatchEdges& edges,
                         std::span<const Vec3> points, const Vec3& normal) {
  patches_ = &patches;
  edges_ = &edges;
  points_ = points;
  normal_ = normal;
  const size_t entries = edges.size() * points.size();
  if (term_.size() < entries) term_.resize(entries);
  ++row_;
}

double ContourCache::FormFactor(uint32_t j, size_t m) {
  const PairPatch& patch = (*patches_)[j];
  const Vec3& x = points_[m];
  double sum = 0;
  for (uint32_t k = 0; k < patch.corners; ++k) {
    const uint32_t slot = edges_->Slot(j, k);
    const bool reversed = slot & 1;
    Term& term = term_[(slot >> 1) * points_.size() + m];
    if (term.row != row_) {
      // The term in the edge's own direction (lower vertex index to higher).
      const uint32_t next = k + 1 == patch.corners ? 0 : k + 1;
      const Vec3& from = patch.corner[reversed ? next : k];
      const Vec3& to = patch.corner[reversed ? k : next];
      term = {ContourEdgeTerm(from - x, to - x, normal_), row_};
    }
    sum += reversed ? -term.value : term.value;
  }
  return FormFactorFromContourSum(sum);
}

}  // namespace radflux
