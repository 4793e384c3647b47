// A bounding-volume hierarchy over a scene's potential blockers (shaft_cull.h filter 1),
// queried with a pair's shaft: the blockers whose polygon may meet the convex hull of i and j.
// A node whose box a separating axis (the coordinate axes, i's and j's normals, the shaft
// direction crossed with the coordinate axes) keeps out of the shaft is skipped whole, so an
// unobstructed pair costs a few box tests and no blocker test; the blockers that reach a leaf
// get the exact per-blocker test (ShaftMayHold). The result is the same set as testing every
// blocker: the node tests use a margin no smaller than the leaf test's.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/formfactor/surface_pair_integrator.h"

namespace radflux {

class BlockerBvh {
 public:
  // A hierarchy over shapes[k] for k in `blockers`; `shapes` must outlive it.
  BlockerBvh(const std::vector<SurfaceShape>& shapes, std::vector<uint32_t> blockers);

  // Sets `out` to the blockers k other than i and j with ShaftMayHold(shapes[i], shapes[j],
  // shapes[k]), in the hierarchy's order.
  void Query(uint32_t i, uint32_t j, std::vector<const SurfaceShape*>& out) const;

  // Number of blockers held.
  size_t size() const { return order_.size(); }

 private:
  struct Node {
    Vec3 center, half;       // the box of the node's blockers, as centre and half extents
    uint32_t first = 0;      // leaf: first index into order_; inner: the right child
    uint32_t count = 0;      // leaf: number of blockers (> 0); inner: 0 (left child is next)
  };
  uint32_t Build(uint32_t begin, uint32_t end);

  const std::vector<SurfaceShape>& shapes_;
  std::vector<uint32_t> order_;  // blocker indices, grouped by leaf
  std::vector<Node> nodes_;      // depth first, root at 0
  double max_diameter_ = 0;      // of the blockers
};

}  // namespace radflux
