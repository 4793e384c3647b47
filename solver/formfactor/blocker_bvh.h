// A bounding-volume hierarchy over a scene's potential blockers (shaft_cull.h filter 1), for
// the two questions a pair (i, j) asks of them:
//   - does any blocker meet the pair's shaft? A node whose box a separating axis (the
//     coordinate axes, i's and j's normals, the shaft direction crossed with the coordinate
//     axes) keeps out of the shaft is skipped whole, and the search stops at the first blocker
//     that passes the exact test (Shaft::MayHold): an unobstructed pair costs a few box tests;
//   - does a segment between them cross a blocker? A segment descends only into the boxes it
//     crosses (slab test), so a pair's segments cost O(log n) each, not one test per blocker.
// The hierarchy is four wide, built by the surface area heuristic; a node holds its four
// children's boxes in single precision (rounded outwards and padded by kFloatPad of the
// scene's extent), so a segment tests all four at once (SSE). Both answers equal testing
// every blocker: the node tests are conservative (the pad is far larger than the rounding of
// the segment to single precision and of the slab arithmetic, and than the leaf test's own).
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

  // Node boxes are widened by this fraction of the largest coordinate magnitude in the
  // scene, R (a segment with an end beyond 2 R tests every blocker instead).
  static constexpr double kFloatPad = 1.0 / 65536;

 private:
  // Four children's boxes, structure of arrays, and what each child is: an inner node
  // (count 0, `child` its index in nodes_) or a leaf (count > 0 blockers from order_[child]).
  // The root is a node even when all blockers fit one leaf.
  struct alignas(16) Node {
    float lo[3][4], hi[3][4];  // scene units; a lane beyond `lanes` is never hit
    uint32_t child[4] = {};
    uint8_t count[4] = {};
    uint32_t lanes = 0;        // children in use (the first `lanes`), 1 to 4
  };
  struct Range {
    uint32_t begin = 0, end = 0;  // into order_
    uint32_t size() const { return end - begin; }
  };
  // A node over order_[range], its children built first; returns its index in nodes_.
  uint32_t BuildNode(Range range, int depth);
  // Splits `range` in two (reordering order_ within it): by the surface area heuristic, or
  // at the median centroid when that fails or the hierarchy is already deep.
  void SplitRange(Range range, int depth, Range& left, Range& right);
  // Walks the children `meets(node, order)` accepts (it returns how many and puts their
  // lanes in `order`, nearest first: leaves are tested in that order, inner nodes visited in
  // it), until `blocks(slot)` holds for the blocker b = order_[slot], b other than i and j;
  // returns b, or kNoBlocker.
  template <class Meets, class Blocks>
  uint32_t AnyBlocker(uint32_t i, uint32_t j, const Meets& meets, const Blocks& blocks) const;

  const std::vector<SurfaceShape>& shapes_;
  std::vector<uint32_t> order_;  // blocker indices, grouped by leaf
  struct Plane {
    Vec3 point, normal;          // the blocker's centroid and normal (SegmentCrossesPlane)
  };
  std::vector<Plane> planes_;    // of order_[slot], at slot: a leaf's planes side by side
  std::vector<Node> nodes_;      // root at 0
  double max_diameter_ = 0;      // of the blockers
  double pad_ = 0;               // box widening for the segment test, scene units
  double reach_ = 0;             // the largest coordinate magnitude of the scene
  Vec3 lo_, hi_;                 // the box of all blockers, widened by pad_
};

}  // namespace radflux
