#include "solver/mesh/face_grouping.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <numbers>
#include <queue>
#include <tuple>
#include <utility>

namespace radflux {
namespace {

constexpr uint32_t kUnassigned = 0xffffffffu;

double TotalFaceArea(const Scene& scene) {
  double total = 0;
  std::vector<Vec3> polygon;
  for (const Face& face : scene.faces) {
    FacePolygonInto(scene, face, polygon);
    total += Length(PolygonNewellNormal(polygon)) / 2;
  }
  return total;
}

// The binary trees of the non-emitting patches (one per (material, sidedness) run of
// `order`), built by top-down median splits, and the cut of them into groups.
class GroupTree {
 public:
  GroupTree(const PatchMesh& mesh, std::vector<uint32_t>& order)
      : mesh_(mesh),
        min_cos_(std::cos(kMaxConeDegrees * std::numbers::pi / 180)),
        order_(order) {}

  // Builds the tree of order[begin, end) and makes it a root.
  void AddRoot(size_t begin, size_t end) { roots_.push_back(Build(begin, end)); }

  // Numbers the nodes of a cut with `budget` nodes (or fewer, when every node of the cut is
  // one patch) into group_of, from `next_group` on.
  void Cut(int64_t budget, std::vector<uint32_t>& group_of, uint32_t& next_group) const {
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
    for (uint32_t k : cut) {
      for (size_t m = nodes_[k].begin; m < nodes_[k].end; ++m) group_of[order_[m]] = next_group;
      ++next_group;
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
    nodes_.push_back({begin, end, {kUnassigned, kUnassigned},
                      std::max(area, (extent / kMaxExtent) * (extent / kMaxExtent)) *
                          (1 + kConeWeight * (1 - min_cos))});
    if (end - begin == 1) return index;
    // Bent (normals beyond the cone): split the normals first; flat: split the centroids.
    const bool by_normal = min_cos < min_cos_;
    const Vec3 spread = by_normal ? n_hi - n_lo : hi - lo;
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
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
  std::vector<uint32_t>& order_;
  std::vector<Node> nodes_;
  std::vector<uint32_t> roots_;
};

}  // namespace

bool GroupsFaces(const Scene& scene, const MeshOptions& options) {
  return options.group_faces && options.max_edge == 0 && options.target_patches > 0 &&
         static_cast<int64_t>(scene.faces.size()) >= options.target_patches;
}

PatchClusters GroupPatches(const Scene& scene, const PatchMesh& mesh, int64_t unknowns) {
  const uint32_t n = static_cast<uint32_t>(mesh.size());
  std::vector<uint32_t> group_of(n, kUnassigned);
  // The non-emitting patches, sorted by (object, material, sidedness): a tree per run.
  std::vector<uint32_t> small;
  uint32_t groups = 0;
  for (uint32_t p = 0; p < n; ++p) {
    if (scene.materials[scene.faces[mesh.patches[p].face].material].IsEmitter()) {
      group_of[p] = groups++;
    } else {
      small.push_back(p);
    }
  }
  const auto set_of = [&](uint32_t p) {
    const Face& face = scene.faces[mesh.patches[p].face];
    return std::make_tuple(face.object, face.material, mesh.patches[p].two_sided);
  };
  std::stable_sort(small.begin(), small.end(),
                   [&](uint32_t a, uint32_t b) { return set_of(a) < set_of(b); });
  GroupTree trees(mesh, small);
  for (size_t begin = 0; begin < small.size();) {
    size_t end = begin + 1;
    while (end < small.size() && set_of(small[end]) == set_of(small[begin])) ++end;
    trees.AddRoot(begin, end);
    begin = end;
  }
  trees.Cut(unknowns - groups, group_of, groups);
  // Number the unknowns in the order of their first patch (emitters and walls keep the
  // scene's order; a group's rows sit near its neighbours').
  std::vector<uint32_t> renumber(groups, kUnassigned), of_patch(n);
  uint32_t next = 0;
  for (uint32_t p = 0; p < n; ++p) {
    uint32_t& u = renumber[group_of[p]];
    if (u == kUnassigned) u = next++;
    of_patch[p] = u;
  }
  return ClustersFromAssignment(mesh, std::move(of_patch), next);
}

absl::StatusOr<GroupedMesh> SubdivideAndGroup(const Scene& scene, const MeshOptions& options) {
  GroupedMesh out;
  if (!GroupsFaces(scene, options)) {
    absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, options);
    if (!mesh.ok()) return mesh.status();
    out.mesh = *std::move(mesh);
    return out;
  }
  const double target_area = TotalFaceArea(scene) / static_cast<double>(options.target_patches);
  MeshOptions split;
  split.max_edge = kSplitEdge * std::sqrt(target_area);
  split.follow_contacts = false;  // the unknowns are groups of faces: no outline to follow
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, split);
  if (!mesh.ok()) return mesh.status();
  out.mesh = *std::move(mesh);
  out.clusters = GroupPatches(scene, out.mesh, options.target_patches);
  return out;
}

}  // namespace radflux
