// LightTree: a binary tree over the emitter patches (bounding sphere, normal cone and power
// per node, after Conty Estevez and Kulla 2018), for choosing one emitter per light sample
// in proportion to an importance: at an inner node whose emitters lie in one plane, the
// exact unoccluded contribution of their bounding rectangle; at other inner nodes,
// power * (a bound on the receiver's cosine) * (a bound on the emitter's cosine) /
// distance^2 from the node's bounds; at a leaf,
// the emitter's exact unoccluded contribution (EmitterImportance), and at a node of two
// leaves the sum of theirs. A choice walks one path
// from the root, so its cost grows with log(emitters), and the rays of a light sample do not
// grow at all. Every emitter that can light the receiver has a non-zero probability (the
// bounds are conservative), which keeps estimates weighted by 1 / probability unbiased.
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

  struct Choice {
    uint32_t emitter = 0;    // index into the tree's emitters
    double probability = 0;  // of choosing it, given (x, n)
  };
  // Chooses an emitter for a receiver at x with unit normal n by u in [0, 1); nothing when
  // no emitter can light x.
  std::optional<Choice> Choose(const Vec3& x, const Vec3& n, double u) const;
  // The probability that Choose picks emitter k at (x, n) (for tests).
  double Probability(const Vec3& x, const Vec3& n, uint32_t k) const;
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

  std::vector<EmitterShape> emitters_;
  std::vector<Node> nodes_;        // nodes_[0] is the root
  std::vector<uint32_t> leaf_of_;  // emitter -> its leaf node
};

}  // namespace radflux
