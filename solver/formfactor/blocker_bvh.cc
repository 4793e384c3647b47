#include "solver/formfactor/blocker_bvh.h"

#include <emmintrin.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/formfactor/shaft_cull.h"
#include "solver/formfactor/shaft_visibility.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {
namespace {

constexpr uint32_t kLeafSize = 4;
constexpr double kRelativeTolerance = 1e-9;  // shaft_cull.cc's margin, relative to the sizes
constexpr int kBins = 16;                    // surface area heuristic: candidate splits a axis
constexpr int kMaxSahDepth = 32;             // deeper nodes split at the median (bounded stack)
constexpr int kStackSize = 256;              // > 3 x (kMaxSahDepth + 32 median levels) + 4
// A segment's direction component below this (single precision) counts as zero: its inverse
// is this large instead of infinite (no 0 x inf in the slab test).
constexpr float kTinyDirection = 1e-30f;

// Rounded down and up to single precision.
float Below(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -HUGE_VALF) : f;
}
float Above(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, HUGE_VALF) : f;
}

struct Box {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void Extend(const Vec3& l, const Vec3& h) {
    lo = {std::min(lo.x, l.x), std::min(lo.y, l.y), std::min(lo.z, l.z)};
    hi = {std::max(hi.x, h.x), std::max(hi.y, h.y), std::max(hi.z, h.z)};
  }
  double HalfArea() const {
    const Vec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

Vec3 BoxCenter(const SurfaceShape& s) { return (s.lo + s.hi) * 0.5; }

}  // namespace

BlockerBvh::BlockerBvh(const std::vector<SurfaceShape>& shapes, std::vector<uint32_t> blockers)
    : shapes_(shapes), order_(std::move(blockers)) {
  double extent = 0;
  for (uint32_t k : order_) {
    max_diameter_ = std::max(max_diameter_, shapes_[k].diameter);
    for (int c = 0; c < 3; ++c) extent = std::max({extent, std::abs(shapes_[k].lo[c]), std::abs(shapes_[k].hi[c])});
  }
  for (const SurfaceShape& s : shapes_) {
    for (int c = 0; c < 3; ++c) reach_ = std::max({reach_, std::abs(s.lo[c]), std::abs(s.hi[c])});
  }
  pad_ = kRelativeTolerance * extent;
  if (order_.empty()) return;
  Box all;
  for (uint32_t k : order_) all.Extend(shapes_[k].lo, shapes_[k].hi);
  const Vec3 pad{pad_, pad_, pad_};
  lo_ = all.lo - pad;
  hi_ = all.hi + pad;
  BuildNode({0, static_cast<uint32_t>(order_.size())}, 0);
  for (uint32_t k : order_) planes_.push_back({shapes_[k].centroid, shapes_[k].normal});
}

void BlockerBvh::SplitRange(Range range, int depth, Range& left, Range& right) {
  Box centers;
  for (uint32_t k = range.begin; k < range.end; ++k) {
    const Vec3 c = BoxCenter(shapes_[order_[k]]);
    centers.Extend(c, c);
  }
  const Vec3 extent = centers.hi - centers.lo;
  double best_cost = HUGE_VAL;
  int best_axis = -1, best_bin = 0;
  const auto bin_of = [&](uint32_t k, int axis) {
    const double f = (BoxCenter(shapes_[k])[axis] - centers.lo[axis]) / extent[axis];
    return std::min(kBins - 1, static_cast<int>(f * kBins));
  };
  for (int axis = 0; axis < 3 && depth < kMaxSahDepth; ++axis) {
    if (!(extent[axis] > 0)) continue;
    std::array<Box, kBins> boxes;
    std::array<uint32_t, kBins> counts{};
    for (uint32_t k = range.begin; k < range.end; ++k) {
      const int bin = bin_of(order_[k], axis);
      boxes[bin].Extend(shapes_[order_[k]].lo, shapes_[order_[k]].hi);
      ++counts[bin];
    }
    std::array<double, kBins> right_cost{};  // of bins [b, kBins)
    Box acc;
    uint32_t n = 0;
    for (int b = kBins - 1; b > 0; --b) {
      acc.Extend(boxes[b].lo, boxes[b].hi);
      n += counts[b];
      right_cost[b] = n > 0 ? acc.HalfArea() * n : 0;
    }
    acc = Box{};
    n = 0;
    for (int b = 1; b < kBins; ++b) {  // left: bins [0, b)
      acc.Extend(boxes[b - 1].lo, boxes[b - 1].hi);
      n += counts[b - 1];
      const double cost = (n > 0 ? acc.HalfArea() * n : 0) + right_cost[b];
      if (n > 0 && n < range.size() && cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
        best_bin = b;
      }
    }
  }
  uint32_t mid;
  if (best_axis >= 0) {
    mid = static_cast<uint32_t>(
        std::partition(order_.begin() + range.begin, order_.begin() + range.end,
                       [&](uint32_t k) { return bin_of(k, best_axis) < best_bin; }) -
        order_.begin());
  } else {  // the median of the centroids along their widest axis
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    mid = range.begin + range.size() / 2;
    std::nth_element(order_.begin() + range.begin, order_.begin() + mid, order_.begin() + range.end,
                     [&](uint32_t a, uint32_t b) { return BoxCenter(shapes_[a])[axis] < BoxCenter(shapes_[b])[axis]; });
  }
  left = {range.begin, mid};
  right = {mid, range.end};
}

uint32_t BlockerBvh::BuildNode(Range range, int depth) {
  // Up to four children: split the largest range above a leaf's size until there are four.
  Range parts[4] = {range};
  int lanes = 1;
  while (lanes < 4) {
    int largest = -1;
    for (int l = 0; l < lanes; ++l) {
      if (parts[l].size() > kLeafSize && (largest < 0 || parts[l].size() > parts[largest].size())) largest = l;
    }
    if (largest < 0) break;
    SplitRange(parts[largest], depth, parts[largest], parts[lanes]);
    ++lanes;
  }
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  const double pad = pad_ + kFloatPad * reach_;
  for (int l = 0; l < lanes; ++l) {
    Box box;
    for (uint32_t k = parts[l].begin; k < parts[l].end; ++k) box.Extend(shapes_[order_[k]].lo, shapes_[order_[k]].hi);
    const bool leaf = parts[l].size() <= kLeafSize;
    const uint32_t child = leaf ? parts[l].begin : BuildNode(parts[l], depth + 1);
    Node& node = nodes_[index];  // after the recursion: nodes_ may have moved
    for (int c = 0; c < 3; ++c) {
      node.lo[c][l] = Below(box.lo[c] - pad);
      node.hi[c][l] = Above(box.hi[c] + pad);
    }
    node.child[l] = child;
    node.count[l] = static_cast<uint8_t>(leaf ? parts[l].size() : 0);
  }
  nodes_[index].lanes = static_cast<uint32_t>(lanes);
  return index;
}

template <class Meets, class Blocks>
uint32_t BlockerBvh::AnyBlocker(uint32_t i, uint32_t j, const Meets& meets, const Blocks& blocks) const {
  if (nodes_.empty()) return kNoBlocker;
  uint32_t stack[kStackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    int order[4];
    const int met = meets(node, order);
    for (int o = 0; o < met; ++o) {  // leaves nearest first
      const int l = order[o];
      for (uint32_t slot = node.child[l]; slot < node.child[l] + node.count[l]; ++slot) {
        const uint32_t b = order_[slot];
        if (b != i && b != j && blocks(slot)) return b;
      }
    }
    for (int o = met - 1; o >= 0; --o) {  // inner nodes: the nearest popped first
      if (node.count[order[o]] == 0) stack[top++] = node.child[order[o]];
    }
  }
  return kNoBlocker;
}

bool BlockerBvh::AnyInShaft(uint32_t i, uint32_t j) const {
  const SurfaceShape& si = shapes_[i];
  const SurfaceShape& sj = shapes_[j];
  const Shaft shaft(si, sj, kRelativeTolerance * (si.diameter + sj.diameter + max_diameter_));
  const auto meets = [&](const Node& node, int (&order)[4]) {
    int met = 0;
    for (uint32_t l = 0; l < node.lanes; ++l) {
      const Vec3 lo{node.lo[0][l], node.lo[1][l], node.lo[2][l]};
      const Vec3 hi{node.hi[0][l], node.hi[1][l], node.hi[2][l]};
      if (shaft.MayMeetBox((lo + hi) * 0.5, (hi - lo) * 0.5)) order[met++] = static_cast<int>(l);
    }
    return met;
  };
  const auto blocks = [&](uint32_t slot) { return shaft.MayHold(shapes_[order_[slot]]); };
  return AnyBlocker(i, j, meets, blocks) != kNoBlocker;
}

bool BlockerBvh::PairMayMeetBlockers(uint32_t i, uint32_t j) const {
  if (nodes_.empty()) return false;
  const SurfaceShape& si = shapes_[i];
  const SurfaceShape& sj = shapes_[j];
  const double margin = pad_ + kRelativeTolerance * (si.diameter + sj.diameter + max_diameter_);
  for (int c = 0; c < 3; ++c) {
    const double lo = std::min(si.lo[c], sj.lo[c]) - margin, hi = std::max(si.hi[c], sj.hi[c]) + margin;
    if (hi < lo_[c] || lo > hi_[c]) return false;
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
  const float origin[3] = {static_cast<float>(a.x), static_cast<float>(a.y),
                           static_cast<float>(a.z)};
  const float direction[3] = {static_cast<float>(d.x), static_cast<float>(d.y),
                              static_cast<float>(d.z)};
  const auto blocks = [&](const SurfaceShape& blocker) {
    return SegmentHitsSurface(a, b, blocker) && MayBlockPair(shapes_[i], shapes_[j], blocker) &&
           !PassesThrough(origin, direction, static_cast<uint32_t>(&blocker - shapes_.data()),
                          blocker.opacity);
  };
  if (last != kNoBlocker && last != i && last != j && blocks(shapes_[last])) return true;
  uint32_t found = kNoBlocker;
  if (std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z), std::abs(b.x), std::abs(b.y),
                std::abs(b.z)}) > 2 * reach_) {  // far outside the scene: the pad may not cover it
    for (uint32_t k : order_) {
      if (k != i && k != j && blocks(shapes_[k])) {
        found = k;
        break;
      }
    }
  } else {
    // Slab test of a + t d, t in [0, 1], against four boxes at once, in single precision.
    __m128 o[3], inv[3];
    for (int c = 0; c < 3; ++c) {
      o[c] = _mm_set1_ps(origin[c]);
      const float dc = direction[c];
      inv[c] = _mm_set1_ps(std::abs(dc) < kTinyDirection ? std::copysign(1 / kTinyDirection, dc) : 1 / dc);
    }
    const auto meets = [&](const Node& node, int (&order)[4]) {
      __m128 t_near = _mm_setzero_ps(), t_far = _mm_set1_ps(1);
      for (int c = 0; c < 3; ++c) {
        const __m128 t0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.lo[c]), o[c]), inv[c]);
        const __m128 t1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.hi[c]), o[c]), inv[c]);
        t_near = _mm_max_ps(t_near, _mm_min_ps(t0, t1));
        t_far = _mm_min_ps(t_far, _mm_max_ps(t0, t1));
      }
      const int mask = _mm_movemask_ps(_mm_cmple_ps(t_near, t_far)) & ((1 << node.lanes) - 1);
      alignas(16) float t[4];
      _mm_store_ps(t, t_near);
      int met = 0;
      for (int l = 0; l < 4; ++l) {  // insertion by entry distance
        if (!(mask & (1 << l))) continue;
        int at = met++;
        for (; at > 0 && t[order[at - 1]] > t[l]; --at) order[at] = order[at - 1];
        order[at] = l;
      }
      return met;
    };
    // A blocker whose plane the segment does not cross is passed over at once (its plane
    // read from planes_, side by side for a leaf, not from its shape).
    const auto crosses_and_blocks = [&](uint32_t slot) {
      return SegmentCrossesPlane(a, b, planes_[slot].point, planes_[slot].normal) &&
             blocks(shapes_[order_[slot]]);
    };
    found = AnyBlocker(i, j, meets, crosses_and_blocks);
  }
  if (found == kNoBlocker) return false;
  last = found;
  return true;
}

}  // namespace radflux
