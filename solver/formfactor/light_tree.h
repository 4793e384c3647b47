// LightTree: a binary tree over the emitter patches (bounding sphere, normal cone and power
// per node, after Conty Estevez and Kulla 2018), for choosing one emitter per light sample
// in proportion to an importance: at an inner node whose emitters lie in one plane, the
// exact unoccluded contribution of their bounding rectangle; at other inner nodes,
// power * (a bound on the receiver's cosine) * (a bound on the emitter's cosine) /
// distance^2 from the node's bounds; at a leaf,
// the emitter's exact unoccluded contribution (EmitterImportance), and at a node of two
// leaves the sum of theirs; from kFarRadii of a leaf's or a plane's radii on, the
// integrand's mean over the polygon's corners instead (FarEmitterImportance: no
// trigonometry, zero where the exact one is, and, as any positive weight, unbiased). A choice
// starts from the receiver point's cut (CutAt: the nodes whose bounds are trustworthy from there,
// opened down to single emitters near the point) and walks one path below the node it picks, so its
// cost grows with log(emitters), and the rays of a light sample do not grow at all. Every emitter
// that can light the receiver has a non-zero probability (the bounds are conservative), which keeps
// estimates weighted by 1 / probability unbiased. A node whose emitters tile a rectangle in one
// plane (a lamp meshed into patches, a luminous ceiling of faces: their areas add up to the
// rectangle's) is "tiled": it is never opened and a walk stops there; the light sample then takes a
// point on the whole rectangle (Shape) and credits the emitter it falls in (Locate), so a tiled
// plane of any number of patches costs what one lamp does.
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

  // One node of a receiver point's cut, with its importance there (> 0). No default values:
  // a Cut's array is left uninitialised (it is set up once per receiver point).
  struct CutNode {
    uint32_t node;
    double importance;
    double form_factor;  // a sampled node's (Sampled) EmitterFormFactor there, or -1
  };
  // A receiver point's cut: nodes that together hold every emitter that can light the point.
  struct Cut {
    std::array<CutNode, kMaxCut> nodes;  // the first `size` are set
    size_t size = 0;
    double total = 0;  // summed importance
  };
  // The cut at receiver point x with unit normal n: from the root, breadth first, every node
  // whose centre is nearer x than kNearField times its radius (every node, when the tree has
  // at most kExactEmitters emitters) is replaced by its two children while the cut has room
  // (kMaxCut); nodes that cannot light x are left out. So an emitter near x is chosen in
  // proportion to its exact contribution against its neighbours', never through an ancestor's
  // far-field bound: F_j(x) / P(j | x) stays within a small multiple of the summed unoccluded
  // form factor of the emitters near x. A tree whose root is sampled (one emitter, or one
  // tiled plane) cuts to the root, importance 1 (form factor -1, not computed) wherever any of
  // it lies in front of x's tangent plane with x in front of it.
  Cut CutAt(const Vec3& x, const Vec3& n) const;

  struct Choice {
    uint32_t node = 0;        // a sampled node (Sampled): a leaf or a tiled node
    double probability = 0;   // of choosing it, given (x, n)
    double form_factor = -1;  // Shape(node)'s EmitterFormFactor at x when the cut has it; else -1
  };
  // Chooses a sampled node (a leaf, or the tiled node above it) for a receiver at x with unit
  // normal n by u in [0, 1), from the cut at (x, n) (CutAt): a cut node in proportion to
  // importance, then the walk below it; nothing when no emitter can light x.
  std::optional<Choice> Choose(const Cut& cut, const Vec3& x, const Vec3& n, double u) const;
  // Whether `cut` holds a single sampled node (one emitter, one tiled plane): Choose then
  // picks it whatever u.
  bool OneChoice(const Cut& cut) const {
    return cut.size == 1 && IsSampled(nodes_[cut.nodes[0].node]);
  }
  // The probability that Choose picks Sampled(k) at (x, n) from `cut` (for tests).
  double Probability(const Cut& cut, const Vec3& x, const Vec3& n, uint32_t k) const;

  // The node a light sample of emitter k samples: its topmost tiled ancestor, else its leaf.
  uint32_t Sampled(uint32_t k) const { return sampled_of_[k]; }
  // Whether `node` is a leaf (Emitter(k) for Locate's k) rather than a tiled rectangle.
  bool IsLeaf(uint32_t node) const { return nodes_[node].emitter >= 0; }
  // The polygon a light sample of sampled node `node` takes its point on: a leaf's emitter, or
  // a tiled node's rectangle (its power the node's summed power; opacity 1).
  const EmitterShape& Shape(uint32_t node) const;
  // The emitter a sample on Shape(node) at point p lights the receiver with: a leaf's own;
  // under a tiled node, the one whose polygon holds p (to within 1e-9 of the node's size),
  // nothing when p is in none.
  std::optional<uint32_t> Locate(uint32_t node, const Vec3& p) const;
  // The distance from x to the bounding box of the nearest emitter that can light (x, n)
  // (one that may, by CanLight); infinity when none can. Walks only the
  // nodes nearer than the best so far.
  double NearestDistance(const Vec3& x, const Vec3& n) const;

 private:
  // The fields a walk reads (Importance) first, in the node's first three cache lines (a far
  // planar node's all of them): the walk is bound by memory, a child's node a cache miss.
  struct alignas(64) Node {
    int64_t emitter = -1;  // leaf: index into emitters_
    int64_t tiled = -1;    // when the emitters' areas add up to bounds_area: its Shape in tiles_
    uint32_t left = 0, right = 0;  // children (inner node)
    // When the node's emitters lie in one plane (a split lamp, a luminous ceiling): the
    // rectangle in that plane that bounds them, front side `axis`; its exact form factor
    // times power / its area is the node's importance (exact when they tile it).
    bool planar = false;
    double power = 0;  // summed over the node's emitters
    Vec3 centre;       // the bounding sphere of the box below
    double radius = 0;
    Vec3 axis;  // normal cone: every emitter normal is within
    std::array<Vec3, 4> bounds_rectangle;
    Vec3 lo, hi;             // bounding box of the emitters' corners
    double cos_spread = -1;  // acos(cos_spread) of axis
    double bounds_area = 0;
    int axis_split = 0;  // the axis their emitters' centres were split along
    uint32_t parent = 0;
  };
  uint32_t Build(std::vector<uint32_t>& order, size_t begin, size_t end, uint32_t parent);
  // Parts order[begin, end) into the emitters facing the first one's side (a positive dot
  // product of normals) and the others, in that order, each part's order kept; returns where
  // the others start, or `begin` when all face one side. A two-sided lamp's twins (MGF: each
  // side lit on its own, at one place) would otherwise stay together down to the leaves, and
  // every node above them face both ways: no cosine bound, no culling, twice the nodes in a
  // cut (RenderPark's corridor, 57 lamps 2 cm under its ceiling: walls and floor 5x noisier).
  size_t PartByFacing(std::vector<uint32_t>& order, size_t begin, size_t end) const;
  // Sorts order[begin, end) along the widest `axis` of the box [lo, hi] and returns the split
  // nearest the median that keeps emitters of one coordinate together.
  size_t SplitAlongWidestAxis(std::vector<uint32_t>& order, size_t begin, size_t end,
                              const Vec3& lo, const Vec3& hi, int& axis) const;
  void BoundPlanar(const std::vector<uint32_t>& order, size_t begin, size_t end, Node& node) const;
  // Makes `node` tiled when planar and its emitters' `area` fills its bounding rectangle.
  void MarkTiled(double area, Node& node);
  // Locate below `node` through every child whose box (widened by `tolerance`) holds p; a
  // polygon holds p within `slack` / |side| of each side.
  std::optional<uint32_t> LocateBelow(uint32_t node, const Vec3& p, double tolerance,
                                      double slack) const;
  // Whether the walk stops at `node`: a leaf or a tiled node.
  bool IsSampled(const Node& node) const { return node.emitter >= 0 || node.tiled >= 0; }
  // A node's importance at (x, n); for a node of two leaves (their sum), also each leaf's
  // into `leaves` when it is set.
  double Importance(const Node& node, const Vec3& x, const Vec3& n,
                    std::optional<std::array<double, 2>>* leaves = nullptr) const;
  // Whether x lies in the near field of inner node `index` (see kNearField).
  bool Opens(uint32_t index, const Vec3& x) const;
  // Whether an emitter under `node` may light x (normal n): x in front of the emitters' plane
  // (a leaf's, a planar node's) and some corner of the node's box in front of x's tangent
  // plane. Conservative, and without a form factor.
  bool CanLight(const Node& node, const Vec3& x, const Vec3& n) const;

  std::vector<EmitterShape> emitters_;
  std::vector<EmitterShape> tiles_;  // the tiled nodes' rectangles
  std::vector<Node> nodes_;          // nodes_[0] is the root
  // A node's children split at `at` along `axis` (left: p[axis] <= at), packed for Locate.
  struct Split {
    double at = 0;
    uint32_t left = 0, right = 0;
    int32_t axis = 0;
    int32_t emitter = -1;  // a leaf's
  };
  std::vector<Split> splits_;         // of nodes_, index for index
  std::vector<uint32_t> leaf_of_;     // emitter -> its leaf node
  std::vector<uint32_t> sampled_of_;  // emitter -> Sampled
};

}  // namespace radflux
