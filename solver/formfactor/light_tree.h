// LightTree: a binary tree over the emitter patches (bounding sphere, normal cone and power
// per node, after Conty Estevez and Kulla 2018), for choosing one emitter per light sample
// in proportion to an importance: at an inner node whose emitters lie in one plane, the
// exact unoccluded contribution of their bounding rectangle; at other inner nodes,
// power * (a bound on the receiver's cosine) * (a bound on the emitter's cosine) /
// distance^2 from the node's bounds; at a leaf,
// the emitter's exact unoccluded contribution (EmitterImportance), and at a node of two
// leaves the sum of theirs. A choice starts from the receiver point's cut (CutAt: the nodes
// whose bounds are trustworthy from there, opened down to single emitters near the point)
// and walks one path below the node it picks, so its cost grows with log(emitters), and the
// rays of a light sample do not grow at all. Every emitter that can light the receiver has a
// non-zero probability (the bounds are conservative), which keeps estimates weighted by
// 1 / probability unbiased.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "solver/formfactor/emitter_shape.h"

namespace radflux {

class LightTree {
 public:
  explicit LightTree(std::vector<EmitterShape> emitters);

  bool empty() const { return emitters_.empty(); }
  uint32_t size() const { return static_cast<uint32_t>(emitters_.size()); }
  const EmitterShape& Emitter(uint32_t k) const { return emitters_[k]; }

  // The most nodes a cut holds.
  static constexpr size_t kMaxCut = 64;
  // A node's importance is a far-field bound: from a point nearer its centre than this many
  // radii it can be off by any factor (a lamp 18 cm from a wall, in a node with the other
  // lamps of its row, was chosen with probability 8e-6 where its exact share was about 0.5,
  // an estimate F / P of 1,400). Beyond, the distance term is within (3 / 2)^2 of the truth.
  static constexpr double kNearField = 3;
  // A tree of at most this many emitters is always cut down to its leaves: every choice is
  // in proportion to the emitters' exact contributions.
  static constexpr uint32_t kExactEmitters = 16;

  // One node of a receiver point's cut, with its importance there (> 0).
  struct CutNode {
    uint32_t node = 0;
    double importance = 0;
    double form_factor = -1;  // a leaf's EmitterFormFactor at the point; -1 for inner nodes
  };
  // A receiver point's cut: nodes that together hold every emitter that can light the point.
  struct Cut {
    std::array<CutNode, kMaxCut> nodes;
    size_t size = 0;
    double total = 0;  // summed importance
  };
  // The cut at receiver point x with unit normal n: from the root, breadth first, every node
  // whose centre is nearer x than kNearField times its radius (every node, when the tree has
  // at most kExactEmitters emitters) is replaced by its two children while the cut has room
  // (kMaxCut); nodes that cannot light x are left out. So an emitter near x is chosen in
  // proportion to its exact contribution against its neighbours', never through an ancestor's
  // far-field bound: F_j(x) / P(j | x) stays within a small multiple of the summed unoccluded
  // form factor of the emitters near x.
  Cut CutAt(const Vec3& x, const Vec3& n) const;

  struct Choice {
    uint32_t emitter = 0;     // index into the tree's emitters
    double probability = 0;   // of choosing it, given (x, n)
    double form_factor = -1;  // its EmitterFormFactor at x when the cut holds it; else -1
  };
  // Chooses an emitter for a receiver at x with unit normal n by u in [0, 1), from the cut at
  // (x, n) (CutAt): a cut node in proportion to importance, then the walk below it; nothing
  // when no emitter can light x.
  std::optional<Choice> Choose(const Cut& cut, const Vec3& x, const Vec3& n, double u) const;
  // The probability that Choose picks emitter k at (x, n) from `cut` (for tests).
  double Probability(const Cut& cut, const Vec3& x, const Vec3& n, uint32_t k) const;
  // The distance from x to the bounding box of the nearest emitter that can light (x, n)
  // (one with a non-zero unoccluded contribution); infinity when none can. Walks only the
  // nodes nearer than the best so far.
  double NearestDistance(const Vec3& x, const Vec3& n) const;

 private:
  struct Node {
    Vec3 lo, hi;  // bounding box of the emitters' corners
    Vec3 centre;  // and its bounding sphere
    double radius = 0;
    Vec3 axis;               // normal cone: every emitter normal is within
    double cos_spread = -1;  // acos(cos_spread) of axis
    double power = 0;        // summed over the node's emitters
    // When the node's emitters lie in one plane (a split lamp, a luminous ceiling): the
    // rectangle in that plane that bounds them, front side `axis`; its exact form factor
    // times power / its area is the node's importance (exact when they tile it).
    bool planar = false;
    std::array<Vec3, 4> bounds_rectangle;
    double bounds_area = 0;
    uint32_t left = 0, right = 0;  // children (inner node)
    int64_t emitter = -1;          // leaf: index into emitters_
    uint32_t parent = 0;
  };
  uint32_t Build(std::vector<uint32_t>& order, size_t begin, size_t end, uint32_t parent);
  void BoundPlanar(const std::vector<uint32_t>& order, size_t begin, size_t end, Node& node) const;
  double Importance(const Node& node, const Vec3& x, const Vec3& n) const;
  // Whether x lies in the near field of inner node `index` (see kNearField).
  bool Opens(uint32_t index, const Vec3& x) const;

  std::vector<EmitterShape> emitters_;
  std::vector<Node> nodes_;        // nodes_[0] is the root
  std::vector<uint32_t> leaf_of_;  // emitter -> its leaf node
};

}  // namespace radflux
