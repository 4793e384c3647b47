#include "solver/formfactor/blocker_bvh.h"

#include <algorithm>
#include <cmath>

#include "solver/formfactor/shaft_cull.h"
#include "solver/formfactor/shaft_visibility.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {
namespace {

constexpr uint32_t kLeafSize = 4;
constexpr double kRelativeTolerance = 1e-9;  // shaft_cull.cc's margin, relative to the sizes

}  // namespace

BlockerBvh::BlockerBvh(const std::vector<SurfaceShape>& shapes, std::vector<uint32_t> blockers)
    : shapes_(shapes), order_(std::move(blockers)) {
  double extent = 0;
  for (uint32_t k : order_) {
    max_diameter_ = std::max(max_diameter_, shapes_[k].diameter);
    for (int c = 0; c < 3; ++c) extent = std::max({extent, std::abs(shapes_[k].lo[c]), std::abs(shapes_[k].hi[c])});
  }
  pad_ = kRelativeTolerance * extent;
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
  const Vec3 pad{pad_, pad_, pad_};
  nodes_.push_back(Node{lo - pad, hi + pad, begin, end - begin});
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
  nodes_[index].axis = static_cast<uint8_t>(axis);
  return index;
}

template <class MeetsBox, class RightFirst, class Blocks>
uint32_t BlockerBvh::AnyBlocker(uint32_t i, uint32_t j, const MeetsBox& meets_box,
                                const RightFirst& right_first, const Blocks& blocks) const {
  if (nodes_.empty()) return kNoBlocker;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const uint32_t index = stack[--top];
    const Node& node = nodes_[index];
    if (!meets_box(node)) continue;
    if (node.count == 0) {
      const bool right = right_first(node);  // the child popped first is pushed last
      stack[top++] = right ? index + 1 : node.first;
      stack[top++] = right ? node.first : index + 1;
      continue;
    }
    for (uint32_t k = node.first; k < node.first + node.count; ++k) {
      const uint32_t b = order_[k];
      if (b != i && b != j && blocks(shapes_[b])) return b;
    }
  }
  return kNoBlocker;
}

bool BlockerBvh::AnyInShaft(uint32_t i, uint32_t j) const {
  const SurfaceShape& si = shapes_[i];
  const SurfaceShape& sj = shapes_[j];
  const Shaft shaft(si, sj, kRelativeTolerance * (si.diameter + sj.diameter + max_diameter_));
  return AnyBlocker(
             i, j,
             [&](const Node& node) {
               return shaft.MayMeetBox((node.lo + node.hi) * 0.5, (node.hi - node.lo) * 0.5);
             },
             [](const Node&) { return false; },
             [&](const SurfaceShape& blocker) { return shaft.MayHold(blocker); }) != kNoBlocker;
}

bool BlockerBvh::PairMayMeetBlockers(uint32_t i, uint32_t j) const {
  if (nodes_.empty()) return false;
  const SurfaceShape& si = shapes_[i];
  const SurfaceShape& sj = shapes_[j];
  const double margin = pad_ + kRelativeTolerance * (si.diameter + sj.diameter + max_diameter_);
  const Node& root = nodes_[0];
  for (int c = 0; c < 3; ++c) {
    const double lo = std::min(si.lo[c], sj.lo[c]) - margin, hi = std::max(si.hi[c], sj.hi[c]) + margin;
    if (hi < root.lo[c] || lo > root.hi[c]) return false;
  }
  return true;
}

bool BlockerBvh::SegmentBlocked(const Vec3& a, const Vec3& b, uint32_t i, uint32_t j) const {
  uint32_t last = kNoBlocker;
  return SegmentBlocked(a, b, i, j, last);
}

bool BlockerBvh::SegmentBlocked(const Vec3& a, const Vec3& b, uint32_t i, uint32_t j,
                                uint32_t& last) const {
  const Vec3 d = b - a;
  const Vec3 inv{1 / d.x, 1 / d.y, 1 / d.z};  // +-inf along an axis the segment does not move
  const float origin[3] = {static_cast<float>(a.x), static_cast<float>(a.y),
                           static_cast<float>(a.z)};
  const float direction[3] = {static_cast<float>(d.x), static_cast<float>(d.y),
                              static_cast<float>(d.z)};
  // Slab test of the segment a + t d, t in [0, 1], against the box (widened a little).
  const auto meets_box = [&](const Node& node) {
    double t0 = 0, t1 = 1;
    for (int c = 0; c < 3; ++c) {
      const double lo = node.lo[c], hi = node.hi[c];
      if (d[c] == 0) {
        if (a[c] < lo || a[c] > hi) return false;
        continue;
      }
      const double ta = (lo - a[c]) * inv[c], tb = (hi - a[c]) * inv[c];
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1;
  };
  const auto blocks = [&](const SurfaceShape& blocker) {
    return SegmentHitsSurface(a, b, blocker) && MayBlockPair(shapes_[i], shapes_[j], blocker) &&
           !PassesThrough(origin, direction, static_cast<uint32_t>(&blocker - shapes_.data()),
                          blocker.opacity);
  };
  if (last != kNoBlocker && last != i && last != j && blocks(shapes_[last])) return true;
  // The child nearer a along the split axis first: a blocked segment stops sooner.
  const uint32_t found =
      AnyBlocker(i, j, meets_box, [&](const Node& node) { return d[node.axis] < 0; }, blocks);
  if (found == kNoBlocker) return false;
  last = found;
  return true;
}

}  // namespace radflux
