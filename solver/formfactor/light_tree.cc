#include "solver/formfactor/light_tree.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

// An angle in [0, pi] by its cosine and sine (sine >= 0): the cone bounds below without
// trigonometric calls (they were an eighth of the corridor's row time).
struct Angle {
  double cos = 1, sin = 0;
};

Angle AngleOfCosine(double c) {
  const double clamped = std::clamp(c, -1.0, 1.0);
  return {clamped, std::sqrt(std::max(0.0, 1 - clamped * clamped))};
}

// max(0, a - b) for angles a, b in [0, pi].
Angle ReducedBy(Angle a, Angle b) {
  if (a.cos >= b.cos) return {};  // a <= b
  return {a.cos * b.cos + a.sin * b.sin, std::max(0.0, a.sin * b.cos - a.cos * b.sin)};
}

// cos(max(0, a - b)), and 0 from a right angle on: the cosine bound of a direction at angle a
// from an axis, known only to within b.
double ClampedCosine(Angle a, Angle b) { return std::max(0.0, ReducedBy(a, b).cos); }

// Distance from x to the box [lo, hi] (0 inside it).
double BoxDistance(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  const Vec3 d{std::max({lo.x - x.x, 0.0, x.x - hi.x}), std::max({lo.y - x.y, 0.0, x.y - hi.y}),
               std::max({lo.z - x.z, 0.0, x.z - hi.z})};
  return Length(d);
}

}  // namespace

LightTree::LightTree(std::vector<EmitterShape> emitters) : emitters_(std::move(emitters)) {
  if (emitters_.empty()) return;
  std::vector<uint32_t> order(emitters_.size());
  for (uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  leaf_of_.resize(emitters_.size());
  nodes_.reserve(2 * emitters_.size());
  Build(order, 0, order.size(), 0);
  for (const Node& node : nodes_) {
    Split split{0, node.left, node.right, 0, static_cast<int32_t>(node.emitter)};
    if (node.emitter < 0)
      split.axis = node.axis_split, split.at = nodes_[node.left].hi[node.axis_split];
    splits_.push_back(split);
  }
  sampled_of_.resize(emitters_.size());
  for (uint32_t k = 0; k < emitters_.size(); ++k) {
    sampled_of_[k] = leaf_of_[k];
    for (uint32_t at = leaf_of_[k]; at != 0;) {
      at = nodes_[at].parent;
      if (nodes_[at].tiled >= 0) sampled_of_[k] = at;
    }
  }
}

size_t LightTree::PartByFacing(std::vector<uint32_t>& order, size_t begin, size_t end) const {
  const Vec3 side = emitters_[order[begin]].normal;
  for (size_t k = begin; k < end; ++k) {
    if (std::abs(Dot(emitters_[order[k]].normal, side)) < 1 - 1e-9) return begin;
  }
  const auto middle =
      std::stable_partition(order.begin() + static_cast<std::ptrdiff_t>(begin),
                            order.begin() + static_cast<std::ptrdiff_t>(end),
                            [&](uint32_t k) { return Dot(emitters_[k].normal, side) > 0; });
  const size_t m = static_cast<size_t>(middle - order.begin());
  return m == end ? begin : m;
}

size_t LightTree::SplitAlongWidestAxis(std::vector<uint32_t>& order, size_t begin, size_t end,
                                       const Vec3& lo, const Vec3& hi, int& axis) const {
  const Vec3 extent = hi - lo;
  axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  // An emitter's place along the axis: the middle of its extent there, the same for the two
  // triangles of a quad, which then stay together (their boxes are one: split apart, the
  // halves' boxes would overlap by a cell and Locate search both).
  auto centre = [&](uint32_t k) {
    const EmitterShape& e = emitters_[k];
    double lo_k = e.corner[0][axis], hi_k = lo_k;
    for (uint32_t c = 1; c < e.corners; ++c) {
      lo_k = std::min(lo_k, e.corner[c][axis]);
      hi_k = std::max(hi_k, e.corner[c][axis]);
    }
    return 0.5 * (lo_k + hi_k);
  };
  std::sort(order.begin() + begin, order.begin() + end, [&](uint32_t a, uint32_t b) {
    return std::make_pair(centre(a), a) < std::make_pair(centre(b), b);
  });
  // The split nearest the median that keeps emitters of one coordinate together, so that
  // the halves of a regular grid (a split lamp) are whole rows or columns: their bounding
  // rectangles are then tiled and their importance exact.
  const double tolerance = 1e-9 * extent[axis];
  auto splits_between = [&](size_t m) {
    return centre(order[m]) - centre(order[m - 1]) > tolerance;
  };
  size_t middle = begin + (end - begin) / 2;
  for (size_t step = 0; step < (end - begin) / 2; ++step) {
    if (splits_between(middle - step)) {
      middle -= step;
      break;
    }
    if (middle + step < end && splits_between(middle + step)) {
      middle += step;
      break;
    }
  }
  return middle;
}

// The subtree of emitters order[begin, end): parted by facing where they face opposite ways,
// else split at the median of the centroids along
// the widest axis of their box (deterministic: ties broken by index).
uint32_t LightTree::Build(std::vector<uint32_t>& order, size_t begin, size_t end, uint32_t parent) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Vec3 lo = emitters_[order[begin]].corner[0], hi = lo, normal_sum;
  double power = 0, area = 0;
  for (size_t k = begin; k < end; ++k) {
    const EmitterShape& e = emitters_[order[k]];
    area += e.area;
    for (const Vec3& c : e.corner) {
      lo = {std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z)};
      hi = {std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z)};
    }
    normal_sum += e.normal * e.area;
    power += e.power;
  }
  Node node;
  node.parent = parent;
  node.lo = lo;
  node.hi = hi;
  node.centre = (lo + hi) * 0.5;
  node.radius = Length(hi - lo) * 0.5;
  node.power = power;
  const double normal_length = Length(normal_sum);
  node.axis = normal_length > 0 ? normal_sum / normal_length : Vec3{0, 0, 1};
  node.cos_spread = normal_length > 0 ? 1.0 : -1.0;
  for (size_t k = begin; k < end && normal_length > 0; ++k) {
    node.cos_spread = std::min(node.cos_spread, Dot(node.axis, emitters_[order[k]].normal));
  }
  BoundPlanar(order, begin, end, node);
  if (end - begin > 1) MarkTiled(area, node);
  if (end - begin == 1) {
    node.emitter = order[begin];
    leaf_of_[order[begin]] = index;
  } else {
    // Emitters facing opposite ways (a normal cone wider than a hemisphere) are parted by the
    // way they face first (PartByFacing); else at the median along the widest axis.
    size_t middle = node.cos_spread < 0 ? PartByFacing(order, begin, end) : begin;
    if (middle == begin) middle = SplitAlongWidestAxis(order, begin, end, lo, hi, node.axis_split);
    node.left = Build(order, begin, middle, index);
    node.right = Build(order, middle, end, index);
  }
  nodes_[index] = node;
  return index;
}

// Sets node.planar and its bounding rectangle when every corner of the emitters
// order[begin, end) lies within 1e-9 of the box's diagonal of the first one's plane and
// every normal is node.axis (to 1e-12).
void LightTree::BoundPlanar(const std::vector<uint32_t>& order, size_t begin, size_t end,
                            Node& node) const {
  if (!(node.cos_spread >= 1 - 1e-12)) return;
  // Sides along the first emitter's first edge and across it: a grid of patches (a meshed
  // lamp) is then bounded by the rectangle it tiles.
  const EmitterShape& first = emitters_[order[begin]];
  const Vec3 edge = first.corner[1] - first.corner[0];
  const Vec3 along = edge - node.axis * Dot(edge, node.axis);
  if (!(Length(along) > 0)) return;
  const Frame frame{Normalize(along), Cross(node.axis, Normalize(along)), node.axis};
  const double offset = Dot(emitters_[order[begin]].corner[0], node.axis);
  const double tolerance = 1e-9 * Length(node.hi - node.lo);
  double s0 = 1e300, s1 = -1e300, t0 = 1e300, t1 = -1e300;
  for (size_t k = begin; k < end; ++k) {
    for (const Vec3& c : emitters_[order[k]].corner) {
      if (std::abs(Dot(c, node.axis) - offset) > tolerance) return;
      const double s = Dot(c, frame.s), t = Dot(c, frame.t);
      s0 = std::min(s0, s), s1 = std::max(s1, s), t0 = std::min(t0, t), t1 = std::max(t1, t);
    }
  }
  const Vec3 base = node.axis * offset;
  // Counter-clockwise about the axis (s x t = axis): the form factor ignores winding anyway.
  node.bounds_rectangle = {base + frame.s * s0 + frame.t * t0, base + frame.s * s1 + frame.t * t0,
                           base + frame.s * s1 + frame.t * t1, base + frame.s * s0 + frame.t * t1};
  node.bounds_area = (s1 - s0) * (t1 - t0);
  node.planar = node.bounds_area > 0;
}

void LightTree::MarkTiled(double area, Node& node) {
  if (!node.planar || !(std::abs(area - node.bounds_area) <= 1e-9 * node.bounds_area)) return;
  EmitterShape shape;
  shape.corner = node.bounds_rectangle;
  shape.corners = 4;
  shape.normal = node.axis;
  shape.area = node.bounds_area;
  shape.power = node.power;
  shape.rectangle = true;
  SetEmitterBounds(shape);
  node.tiled = static_cast<int64_t>(tiles_.size());
  tiles_.push_back(shape);
}

const EmitterShape& LightTree::Shape(uint32_t node) const {
  const Node& at = nodes_[node];
  return at.emitter >= 0 ? emitters_[at.emitter] : tiles_[at.tiled];
}

namespace {

// Whether the box [lo, hi] widened by `tolerance` holds p.
bool BoxHolds(const Vec3& lo, const Vec3& hi, const Vec3& p, double tolerance) {
  return p.x >= lo.x - tolerance && p.x <= hi.x + tolerance && p.y >= lo.y - tolerance &&
         p.y <= hi.y + tolerance && p.z >= lo.z - tolerance && p.z <= hi.z + tolerance;
}

// Whether emitter e's polygon holds p, to within `slack` / |side| of each side.
bool PolygonHolds(const EmitterShape& e, const Vec3& p, double slack) {
  for (uint32_t k = 0; k < e.corners; ++k) {
    const Vec3 side = e.corner[(k + 1) % e.corners] - e.corner[k];
    if (Dot(Cross(side, p - e.corner[k]), e.normal) < -slack) return false;
  }
  return true;
}

}  // namespace

std::optional<uint32_t> LightTree::Locate(uint32_t node, const Vec3& p) const {
  if (nodes_[node].emitter >= 0) return static_cast<uint32_t>(nodes_[node].emitter);
  // Boxes widened by 1e-9 of the node's radius r; a polygon's sides by that times 2 r / |side|
  // (2 r bounds every side).
  const double tolerance = 1e-9 * nodes_[node].radius;
  const double slack = tolerance * 2 * nodes_[node].radius;
  // Straight down by the split planes: where siblings do not overlap (a grid's halves) this
  // is the only path. Else (a quad's two triangles split apart) back up it, through each
  // sibling whose box holds p, nearest first; the whole node last, if the path overflows.
  std::array<uint32_t, 64> path;
  size_t depth = 0;
  uint32_t at = node;
  while (splits_[at].emitter < 0) {
    const Split& inner = splits_[at];
    if (depth < path.size()) path[depth++] = at;
    at = p[inner.axis] <= inner.at ? inner.left : inner.right;
  }
  if (PolygonHolds(emitters_[splits_[at].emitter], p, slack)) {
    return static_cast<uint32_t>(splits_[at].emitter);
  }
  for (size_t level = depth; level-- > 0;) {
    const Split& up = splits_[path[level]];
    const uint32_t taken = level + 1 < depth ? path[level + 1] : at;
    const uint32_t sibling = up.left == taken ? up.right : up.left;
    if (!BoxHolds(nodes_[sibling].lo, nodes_[sibling].hi, p, tolerance)) continue;
    if (const auto found = LocateBelow(sibling, p, tolerance, slack)) return found;
  }
  return depth < path.size() ? std::nullopt : LocateBelow(node, p, tolerance, slack);
}

// Depth first down every child whose box holds p.
std::optional<uint32_t> LightTree::LocateBelow(uint32_t node, const Vec3& p, double tolerance,
                                               double slack) const {
  const Node& at = nodes_[node];
  if (at.emitter >= 0) {
    if (!PolygonHolds(emitters_[at.emitter], p, slack)) return std::nullopt;
    return static_cast<uint32_t>(at.emitter);
  }
  for (const uint32_t child : {at.left, at.right}) {
    if (!BoxHolds(nodes_[child].lo, nodes_[child].hi, p, tolerance)) continue;
    if (const auto found = LocateBelow(child, p, tolerance, slack)) return found;
  }
  return std::nullopt;
}

namespace {

// Whether x lies at least kFarRadii radii from a centre (ReachOf's far).
bool IsFar(const Vec3& centre, double radius, const Vec3& x) {
  const Vec3 d = centre - x;
  return Dot(d, d) >= kFarRadii * kFarRadii * radius * radius;
}

// Whether some corner of the box [lo, hi] lies in front of the plane through x with unit
// normal n: the one farthest in front, which takes on each axis the side n points to (one
// corner's dot product in place of eight).
bool BoxInFront(const Vec3& lo, const Vec3& hi, const Vec3& x, const Vec3& n) {
  const Vec3 front{n.x > 0 ? hi.x : lo.x, n.y > 0 ? hi.y : lo.y, n.z > 0 ? hi.z : lo.z};
  return Dot(front - x, n) > 0;
}

// A sampled node's (an emitter's, a tiled rectangle's) importance at (x, n): from its exact
// form factor, put into `form_factor`; from kFarRadii of its radii on FarEmitterImportance,
// and `form_factor` -1 (not computed).
double SampledImportance(const EmitterShape& shape, const Vec3& x, const Vec3& n,
                         double& form_factor) {
  if (IsFar(shape.centre, shape.radius, x)) {
    form_factor = -1;
    return FarEmitterImportance(std::span<const Vec3>(shape.corner.data(), shape.corners),
                                shape.normal, shape.power, x, n);
  }
  form_factor = EmitterFormFactor(shape, x, n);
  return EmitterImportance(shape, form_factor);
}

}  // namespace

double LightTree::Importance(const Node& node, const Vec3& x, const Vec3& n,
                             std::optional<std::array<double, 2>>* leaves) const {
  double unused;
  if (node.emitter >= 0) return SampledImportance(emitters_[node.emitter], x, n, unused);
  if (node.tiled >= 0) return SampledImportance(tiles_[node.tiled], x, n, unused);
  // A node of two leaves: their sum, so that no walk ends at a pair that cannot light x.
  const Node& left = nodes_[node.left];
  const Node& right = nodes_[node.right];
  if (left.emitter >= 0 && right.emitter >= 0) {
    const double l = SampledImportance(emitters_[left.emitter], x, n, unused);
    const double r = SampledImportance(emitters_[right.emitter], x, n, unused);
    if (leaves != nullptr) *leaves = std::array<double, 2>{l, r};
    return l + r;
  }
  if (node.planar) {
    if (!(Dot(x - node.bounds_rectangle[0], node.axis) > 0)) return 0;  // x behind the plane
    if (IsFar(node.centre, node.radius, x)) {
      return FarEmitterImportance(node.bounds_rectangle, node.axis, node.power, x, n);
    }
    const double form_factor = PointToPolygonFormFactor(x, n, node.bounds_rectangle);
    return node.power / node.bounds_area * std::numbers::pi * form_factor;
  }
  // Every corner of the node's box behind (or on) x's tangent plane: nothing to see.
  if (!BoxInFront(node.lo, node.hi, x, n)) return 0;
  const Vec3 d = node.centre - x;
  const double distance2 = Dot(d, d);
  const double radius2 = node.radius * node.radius;
  // x inside the sphere: no cosine bound; the distance term alone steers towards the nearer
  // part (any positive weight keeps the choice unbiased; only the bounds must be conservative).
  if (distance2 <= radius2) return node.power / std::max(distance2, 1e-2 * radius2);
  const double distance = std::sqrt(distance2);
  const double ratio = node.radius / distance;
  const Angle spread{std::sqrt(1 - ratio * ratio), ratio};  // half-angle of the sphere at x
  const Vec3 towards = d / distance;
  const double receiver = ClampedCosine(AngleOfCosine(Dot(n, towards)), spread);
  const double emitter = ClampedCosine(
      ReducedBy(AngleOfCosine(-Dot(node.axis, towards)), AngleOfCosine(node.cos_spread)), spread);
  return node.power * receiver * emitter / distance2;
}

bool LightTree::Opens(uint32_t index, const Vec3& x) const {
  const Node& node = nodes_[index];
  if (IsSampled(node)) return false;
  if (size() <= kExactEmitters) return true;
  const Vec3 d = node.centre - x;
  return Dot(d, d) < kNearField * kNearField * node.radius * node.radius;
}

bool LightTree::CanLight(const Node& node, const Vec3& x, const Vec3& n) const {
  if (node.planar && !(Dot(x - node.bounds_rectangle[0], node.axis) > 0)) return false;
  if (node.emitter >= 0) {
    const EmitterShape& e = emitters_[node.emitter];
    if (!(Dot(x - e.corner[0], e.normal) > 0)) return false;
  }
  return BoxInFront(node.lo, node.hi, x, n);
}

LightTree::Cut LightTree::CutAt(const Vec3& x, const Vec3& n) const {
  Cut cut;
  if (nodes_.empty()) return cut;
  if (IsSampled(nodes_[0])) {  // one emitter, or one tiled plane: its share is 1 wherever
    const EmitterShape& shape = Shape(0);  // it can light x at all
    bool any_front = false;
    for (uint32_t k = 0; k < shape.corners; ++k) any_front |= Dot(shape.corner[k] - x, n) > 0;
    if (any_front && Dot(x - shape.corner[0], shape.normal) > 0) {
      cut.nodes[0] = {0, 1, -1};
      cut.size = 1;
      cut.total = 1;
    }
    return cut;
  }
  // Level by level: `level` holds the nodes met at one depth, opened ones give the next.
  std::array<uint32_t, kMaxCut> level, next;
  size_t level_size = 1, kept = 0;  // kept: nodes already final in `cut`
  level[0] = 0;
  while (level_size > 0) {
    size_t next_size = 0;
    for (size_t k = 0; k < level_size; ++k) {
      const uint32_t index = level[k];
      // Opening adds one node to the cut; the rest of this level and the next take room.
      if (Opens(index, x) && kept + (level_size - k) + next_size + 1 <= kMaxCut) {
        next[next_size++] = nodes_[index].left;
        next[next_size++] = nodes_[index].right;
        continue;
      }
      const Node& node = nodes_[index];
      CutNode entry{index, 0, -1};
      if (IsSampled(node)) {
        entry.importance = SampledImportance(Shape(index), x, n, entry.form_factor);
      } else {
        entry.importance = Importance(node, x, n);
      }
      ++kept;
      if (!(entry.importance > 0)) continue;
      cut.nodes[cut.size++] = entry;
      cut.total += entry.importance;
    }
    std::copy_n(next.begin(), next_size, level.begin());
    level_size = next_size;
  }
  return cut;
}

std::optional<LightTree::Choice> LightTree::Choose(const Cut& cut, const Vec3& x, const Vec3& n,
                                                   double u) const {
  if (cut.size == 0 || !(cut.total > 0)) return std::nullopt;
  const double target = u * cut.total;
  size_t pick = 0;
  double below = cut.nodes[0].importance;
  while (pick + 1 < cut.size && !(target < below)) below += cut.nodes[++pick].importance;
  const CutNode& entry = cut.nodes[pick];
  double probability = entry.importance / cut.total;
  u = std::clamp((target - (below - entry.importance)) / entry.importance, 0.0,
                 0x1.fffffffffffffp-1);
  uint32_t at = entry.node;
  // A node of two leaves weighs as their sum (Importance): the walk that enters one keeps its
  // leaves' terms instead of evaluating them again.
  std::optional<std::array<double, 2>> leaves;  // at's, when known
  while (!IsSampled(nodes_[at])) {
    const Node& node = nodes_[at];
    std::optional<std::array<double, 2>> left_leaves, right_leaves;
    const double left = leaves ? (*leaves)[0] : Importance(nodes_[node.left], x, n, &left_leaves);
    const double right =
        leaves ? (*leaves)[1] : Importance(nodes_[node.right], x, n, &right_leaves);
    if (!(left + right > 0)) return std::nullopt;
    const double p_left = left / (left + right);
    if (u < p_left) {
      at = node.left;
      leaves = left_leaves;
      probability *= p_left;
      u = std::min(u / p_left, 0x1.fffffffffffffp-1);
    } else {
      at = node.right;
      leaves = right_leaves;
      probability *= 1 - p_left;
      u = std::min((u - p_left) / (1 - p_left), 0x1.fffffffffffffp-1);
    }
  }
  if (!(probability > 0)) return std::nullopt;
  return Choice{at, probability, at == entry.node ? entry.form_factor : -1.0};
}

double LightTree::Probability(const Cut& cut, const Vec3& x, const Vec3& n, uint32_t k) const {
  double probability = 1;
  for (uint32_t at = sampled_of_[k];; at = nodes_[at].parent) {
    for (size_t c = 0; c < cut.size; ++c) {
      if (cut.nodes[c].node == at) return probability * cut.nodes[c].importance / cut.total;
    }
    if (at == 0) return 0;
    const Node& parent = nodes_[nodes_[at].parent];
    const double left = Importance(nodes_[parent.left], x, n);
    const double right = Importance(nodes_[parent.right], x, n);
    if (!(left + right > 0)) return 0;
    probability *= (at == parent.left ? left : right) / (left + right);
  }
}

double LightTree::NearestDistance(const Vec3& x, const Vec3& n) const {
  double best = INFINITY;
  // Per-thread scratch, reused row to row: no allocation once warm (absl::InlinedVector here
  // trips GCC 12's -Wmaybe-uninitialized under the sanitizers).
  thread_local std::vector<uint32_t> stack;
  stack.clear();
  if (!nodes_.empty()) stack.push_back(0);
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    const double distance = BoxDistance(x, node.lo, node.hi);
    if (distance >= best || !CanLight(node, x, n)) continue;
    if (IsSampled(node)) {
      best = distance;
    } else {
      stack.push_back(node.left);
      stack.push_back(node.right);
    }
  }
  return best;
}

}  // namespace radflux
