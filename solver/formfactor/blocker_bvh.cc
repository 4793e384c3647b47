#include "solver/formfactor/blocker_bvh.h"

#include <algorithm>
#include <cmath>

#include "solver/formfactor/shaft_cull.h"

namespace radflux {
namespace {

constexpr uint32_t kLeafSize = 4;
constexpr double kRelativeTolerance = 1e-9;  // shaft_cull.cc's margin, relative to the sizes

}  // namespace

BlockerBvh::BlockerBvh(const std::vector<SurfaceShape>& shapes, std::vector<uint32_t> blockers)
    : shapes_(shapes), order_(std::move(blockers)) {
  for (uint32_t k : order_) max_diameter_ = std::max(max_diameter_, shapes_[k].diameter);
  if (!order_.empty()) Build(0, static_cast<uint32_t>(order_.size()));
}

uint32_t BlockerBvh::Build(uint32_t begin, uint32_t end) {
  Vec3 lo = shapes_[order_[begin]].lo, hi = shapes_[order_[begin]].hi;
  Vec3 clo = shapes_[order_[begin]].centroid, chi = clo;
  for (uint32_t k = begin; k < end; ++k) {
    const SurfaceShape& s = shapes_[order_[k]];
    lo = {std::min(lo.x, s.lo.x), std::min(lo.y, s.lo.y), std::min(lo.z, s.lo.z)};
    hi = {std::max(hi.x, s.hi.x), std::max(hi.y, s.hi.y), std::max(hi.z, s.hi.z)};
    clo = {std::min(clo.x, s.centroid.x), std::min(clo.y, s.centroid.y), std::min(clo.z, s.centroid.z)};
    chi = {std::max(chi.x, s.centroid.x), std::max(chi.y, s.centroid.y), std::max(chi.z, s.centroid.z)};
  }
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back(Node{(lo + hi) * 0.5, (hi - lo) * 0.5, begin, end - begin});
  if (end - begin <= kLeafSize) return index;
  const Vec3 extent = chi - clo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](uint32_t a, uint32_t b) {
                     return shapes_[a].centroid[axis] < shapes_[b].centroid[axis];
                   });
  Build(begin, mid);
  const uint32_t right = Build(mid, end);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

bool BlockerBvh::InShaft(uint32_t i, uint32_t j, std::vector<uint32_t>& out) const {
  out.clear();
  if (nodes_.empty()) return false;
  const SurfaceShape& si = shapes_[i];
  const SurfaceShape& sj = shapes_[j];
  const Shaft shaft(si, sj, kRelativeTolerance * (si.diameter + sj.diameter + max_diameter_));
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const uint32_t index = stack[--top];
    const Node& node = nodes_[index];
    if (!shaft.MayMeetBox(node.center, node.half)) continue;
    if (node.count == 0) {
      stack[top++] = node.first;
      stack[top++] = index + 1;
      continue;
    }
    for (uint32_t k = node.first; k < node.first + node.count; ++k) {
      const uint32_t b = order_[k];
      const SurfaceShape& s = shapes_[b];
      if (b != i && b != j && shaft.MayMeetBounds(s.lo, s.hi) &&
          MayBlockPair(si, sj, s)) {
        out.push_back(b);
      }
    }
  }
  return std::any_of(out.begin(), out.end(), [&](uint32_t b) { return shaft.MayHold(shapes_[b]); });
}

}  // namespace radflux
