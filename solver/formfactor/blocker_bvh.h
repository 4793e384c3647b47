// A bounding-volume hierarchy over a scene's potential blockers (shaft_cull.h filter 1), for
// the question a pair (i, j) asks of them: which blockers may meet the pair's shaft? A node
// whose box a separating axis (the coordinate axes, i's and j's normals, the shaft direction
// crossed with the coordinate axes) keeps out of the shaft is skipped whole: an unobstructed
// pair costs a few box tests. The node tests are conservative (with a margin no smaller than
// the leaf test's), so nothing that may block the pair is missed.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/core/vec3.h"

#include "solver/formfactor/surface_pair_integrator.h"

namespace radflux {

class BlockerBvh {
 public:
  // A hierarchy over shapes[k] for k in `blockers`; `shapes` must outlive it.
  BlockerBvh(const std::vector<SurfaceShape>& shapes, std::vector<uint32_t> blockers);

  // Into `out` (cleared first), in no particular order: every blocker k other than i and j
  // whose bounding box may meet the shaft of i and j and that may block the pair
  // (MayBlockPair, shaft_cull.h), a superset of those that may meet the shaft. Returns whether
  // one of them does (ShaftMayHold(shapes[i], shapes[j], shapes[k]) for some k): when not,
  // nothing can hide part of j from i.
  bool InShaft(uint32_t i, uint32_t j, std::vector<uint32_t>& out) const;

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
