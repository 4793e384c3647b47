#include "solver/mesh/face_grouping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <tuple>
#include <utility>

namespace radflux {
namespace {

constexpr uint32_t kUnassigned = 0xffffffffu;

// The binary trees of the non-emitting patches (one per (object, material, sidedness, side,
// direct light) run of `order`), built by top-down median splits, and the cut of them into groups.
class GroupTree {
 public:
  // `target_area`: a*, the area of a group of the cut when the budget spreads evenly.
  GroupTree(const PatchMesh& mesh, std::vector<uint32_t>& order, double target_area)
      : mesh_(mesh),
        min_cos_(std::cos(kMaxConeDegrees * std::numbers::pi / 180)),
        normal_split_extent_(kMaxExtent * std::sqrt(target_area)),
        order_(order) {}

  // Builds the tree of order[begin, end) and makes it a root.
  void AddRoot(size_t begin, size_t end) { roots_.push_back(Build(begin, end)); }

  // The nodes of the cut with `budget` nodes (or fewer, when every node of the cut is one
  // patch), in index order. The cut is greedy (largest priority first), so a larger budget
  // gives a refinement of a smaller one: each of its nodes lies inside one of the smaller's.
  std::vector<uint32_t> CutNodes(int64_t budget) const {
    std::priority_queue<std::pair<double, uint32_t>> open;
    for (uint32_t r : roots_) open.push({nodes_[r].priority, r});
    std::vector<uint32_t> cut;
    int64_t count = static_cast<int64_t>(roots_.size());
    while (!open.empty() && count < budget) {
      const uint32_t k = open.top().second;
      open.pop();
      if (nodes_[k].child[0] == kUnassigned) {
        cut.push_back(k);
        continue;
      }
      for (uint32_t c : nodes_[k].child) open.push({nodes_[c].priority, c});
      ++count;
    }
    for (; !open.empty(); open.pop()) cut.push_back(open.top().second);
    std::sort(cut.begin(), cut.end());
    return cut;
  }

  // Numbers the patches of each node of `cut` into set_of, one number per node from `next` on.
  void Number(const std::vector<uint32_t>& cut, std::vector<uint32_t>& set_of,
              uint32_t& next) const {
    for (uint32_t k : cut) {
      for (size_t m = nodes_[k].begin; m < nodes_[k].end; ++m) set_of[order_[m]] = next;
      ++next;
    }
  }

 private:
  struct Node {
    size_t begin = 0, end = 0;  // its patches: order_[begin, end)
    std::array<uint32_t, 2> child{kUnassigned, kUnassigned};
    double priority = 0;  // the cut splits the node of largest priority first
  };

  uint32_t Build(size_t begin, size_t end) {
    Vec3 lo = mesh_.patches[order_[begin]].centroid, hi = lo, mean_normal;
    Vec3 n_lo = mesh_.patches[order_[begin]].normal, n_hi = n_lo;
    double area = 0;
    for (size_t k = begin; k < end; ++k) {
      const Patch& p = mesh_.patches[order_[k]];
      lo = Min(lo, p.centroid), hi = Max(hi, p.centroid);
      n_lo = Min(n_lo, p.normal), n_hi = Max(n_hi, p.normal);
      mean_normal += p.normal * p.area;
      area += p.area;
    }
    const Vec3 axis_normal = Length(mean_normal) > 0 ? Normalize(mean_normal) : Vec3{};
    double min_cos = 1;
    for (size_t k = begin; k < end; ++k) {
      min_cos = std::min(min_cos, Dot(mesh_.patches[order_[k]].normal, axis_normal));
    }
    const double extent = Length(hi - lo);
    const uint32_t index = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back({begin,
                      end,
                      {kUnassigned, kUnassigned},
                      std::max(area, (extent / kMaxExtent) * (extent / kMaxExtent)) *
                          (1 + kConeWeight * (1 - min_cos))});
    if (end - begin == 1) return index;
    // Bent (normals beyond the cone) and no larger than a group: split the normals; else
    // split the centroids (a bent node spanning the scene, all chairs of a room, is split in
    // space first: split by normals, its children would span the room as it does).
    const bool by_normal = min_cos < min_cos_ && extent <= normal_split_extent_;
    const Vec3 spread = by_normal ? n_hi - n_lo : hi - lo;
    const int axis =
        spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    const auto key = [&](uint32_t p) {
      const Vec3& v = by_normal ? mesh_.patches[p].normal : mesh_.patches[p].centroid;
      return std::make_pair(axis == 0 ? v.x : (axis == 1 ? v.y : v.z), p);
    };
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(begin),
                     order_.begin() + static_cast<std::ptrdiff_t>(mid),
                     order_.begin() + static_cast<std::ptrdiff_t>(end),
                     [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    const uint32_t left = Build(begin, mid);
    const uint32_t right = Build(mid, end);
    nodes_[index].child = {left, right};
    return index;
  }

  static Vec3 Min(const Vec3& a, const Vec3& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
  }
  static Vec3 Max(const Vec3& a, const Vec3& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
  }

  const PatchMesh& mesh_;
  double min_cos_;
  double normal_split_extent_;  // scene units
  std::vector<uint32_t>& order_;
  std::vector<Node> nodes_;
  std::vector<uint32_t> roots_;
};

// Renumbers sets (0..count-1 in set_of) in the order of their first patch (emitters and walls
// keep the scene's order; a set's rows sit near its neighbours').
PatchClusters NumberByFirstPatch(const PatchMesh& mesh, const std::vector<uint32_t>& set_of,
                                 uint32_t count) {
  std::vector<uint32_t> renumber(count, kUnassigned), of_patch(set_of.size());
  uint32_t next = 0;
  for (uint32_t p = 0; p < set_of.size(); ++p) {
    uint32_t& u = renumber[set_of[p]];
    if (u == kUnassigned) u = next++;
    of_patch[p] = u;
  }
  return ClustersFromAssignment(mesh, std::move(of_patch), next);
}

}  // namespace

bool GroupsFaces(const Scene& scene, const MeshOptions& options) {
  return options.group_faces && options.max_edge == 0 && options.target_patches > 0 &&
         static_cast<int64_t>(scene.faces.size()) >= options.target_patches;
}

PatchClusters GroupPatches(const Scene& scene, const PatchMesh& mesh, int64_t unknowns,
                           PatchClusters* cells, const std::vector<DirectLight>& light) {
  const uint32_t n = static_cast<uint32_t>(mesh.size());
  std::vector<uint32_t> group_of(n, kUnassigned);
  // The patches that are not unknowns of their own (emitters, hidden patches), sorted by
  // (object, material, sidedness, side, direct light): a tree per run.
  std::vector<uint32_t> small;
  uint32_t singles = 0;
  for (uint32_t p = 0; p < n; ++p) {
    if (mesh.patches[p].hidden ||
        scene.materials[scene.faces[mesh.patches[p].face].material].IsEmitter() ||
        (!light.empty() && light[p] == DirectLight::kBright)) {
      group_of[p] = singles++;
    } else {
      small.push_back(p);
    }
  }
  const auto set_of = [&](uint32_t p) {
    const Face& face = scene.faces[mesh.patches[p].face];
    return std::make_tuple(face.object, face.material, mesh.patches[p].two_sided, face.back_face,
                           light.empty() ? DirectLight::kUnlit : light[p]);
  };
  std::stable_sort(small.begin(), small.end(),
                   [&](uint32_t a, uint32_t b) { return set_of(a) < set_of(b); });
  double small_area = 0;
  for (uint32_t p : small) small_area += mesh.patches[p].area;
  GroupTree trees(mesh, small,
                  small_area / static_cast<double>(std::max<int64_t>(unknowns - singles, 1)));
  int64_t roots = 0;
  for (size_t begin = 0; begin < small.size();) {
    size_t end = begin + 1;
    while (end < small.size() && set_of(small[end]) == set_of(small[begin])) ++end;
    trees.AddRoot(begin, end);
    ++roots;
    begin = end;
  }
  // The groups' budget: what the singles leave of `unknowns`, but never less than a group per
  // tree, so that the cells keep kDirectCellsPerUnknown per group when the singles alone reach
  // the target (a lamp in its housing meshed alone at --patches 20: 50 singles, 3 groups, and
  // no cells left, so the tube saw its housing's mean and absorbed a third of its share).
  const int64_t budget = std::max(unknowns - singles, roots);
  if (cells != nullptr) {
    std::vector<uint32_t> cell_of = group_of;
    uint32_t count = singles;
    trees.Number(trees.CutNodes(kDirectCellsPerUnknown * budget), cell_of, count);
    *cells = NumberByFirstPatch(mesh, cell_of, count);
  }
  uint32_t groups = singles;
  trees.Number(trees.CutNodes(budget), group_of, groups);
  return NumberByFirstPatch(mesh, group_of, groups);
}

absl::StatusOr<PatchMesh> SubdivideForGrouping(const Scene& scene, const MeshOptions& options,
                                               const QuadCutsByFace& cuts) {
  const double target_area = TotalFaceArea(scene) / static_cast<double>(options.target_patches);
  MeshOptions split;
  split.max_edge = kSplitEdge * std::sqrt(target_area);
  split.follow_contacts = options.follow_contacts;
  split.min_contact_area = target_area;  // faces of a patch or more (face_grouping.h)
  return SubdivideScene(scene, split, cuts);
}

}  // namespace radflux
