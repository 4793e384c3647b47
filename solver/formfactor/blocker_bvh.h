// A bounding-volume hierarchy over a scene's potential blockers (shaft_cull.h filter 1), for
// the two questions a pair (i, j) asks of them:
//   - does any blocker meet the pair's shaft? A node whose box a separating axis (the
//     coordinate axes, i's and j's normals, the shaft direction crossed with the coordinate
//     axes) keeps out of the shaft is skipped whole, and the search stops at the first blocker
//     that passes the exact test (Shaft::MayHold): an unobstructed pair costs a few box tests;
//   - does a segment between them cross a blocker? A segment descends only into the boxes it
//     crosses (slab test), so a pair's segments cost O(log n) each, not one test per blocker.
// Both answers equal testing every blocker: the node tests are conservative (with a margin no
// smaller than the leaf test's).
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

  // Whether some blocker k other than i and j may meet the shaft of i and j
  // (ShaftMayHold(shapes[i], shapes[j], shapes[k]) for some k).
  bool AnyInShaft(uint32_t i, uint32_t j) const;

  // False when the bounding box of i and j (widened by both tests' margins) misses the box of
  // all blockers: then neither AnyInShaft(i, j) nor a segment between them finds one.
  bool PairMayMeetBlockers(uint32_t i, uint32_t j) const;

  // Whether the open segment from a to b crosses a blocker other than i and j that may block
  // the pair (SegmentHitsSurface, shaft_visibility.h, and MayBlockPair, shaft_cull.h: i's
  // back-face twin, or a face in i's or j's plane, never blocks the segments between them),
  // and that does not let it through: a partly transparent blocker (SurfaceShape::opacity)
  // lets it through as PassesThrough (ray_caster.h) decides for the segment as a ray.
  bool SegmentBlocked(const Vec3& a, const Vec3& b, uint32_t i, uint32_t j) const;

  // The same answer, testing `last` first when it names a blocker (kNoBlocker: none), and
  // setting it to the blocker found: the segments of one pair are coherent, and the blocker
  // that hid the previous one often hides the next, which then costs no hierarchy walk.
  static constexpr uint32_t kNoBlocker = UINT32_MAX;
  bool SegmentBlocked(const Vec3& a, const Vec3& b, uint32_t i, uint32_t j, uint32_t& last) const;

  // Number of blockers held.
  size_t size() const { return order_.size(); }

 private:
  struct Node {
    Vec3 lo, hi;             // the box of the node's blockers, widened by pad_
    uint32_t first = 0;      // leaf: first index into order_; inner: the right child
    uint32_t count = 0;      // leaf: number of blockers (> 0); inner: 0 (left child is next)
    uint8_t axis = 0;        // inner: the split axis (left child: the lower centroids)
  };
  uint32_t Build(uint32_t begin, uint32_t end);
  // Walks the nodes whose box `meets_box(node)` accepts, the children in the order
  // `right_first(node)` says, until `blocks(b)` holds for a blocker b other than i and j;
  // returns b, or kNoBlocker.
  template <class MeetsBox, class RightFirst, class Blocks>
  uint32_t AnyBlocker(uint32_t i, uint32_t j, const MeetsBox& meets_box, const RightFirst& right_first,
                  const Blocks& blocks) const;

  const std::vector<SurfaceShape>& shapes_;
  std::vector<uint32_t> order_;  // blocker indices, grouped by leaf
  std::vector<Node> nodes_;      // depth first, root at 0
  double max_diameter_ = 0;      // of the blockers
  double pad_ = 0;               // box widening for the segment test, scene units
};

}  // namespace radflux
