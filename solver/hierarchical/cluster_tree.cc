#include "solver/hierarchical/cluster_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace radflux {
namespace {

// Sorts order[begin, end) about its median along the longest axis of the centroid bounds.
void MedianSplit(const ElementTree& tree, std::vector<uint32_t>& order, uint32_t begin,
                 uint32_t mid, uint32_t end) {
  double lo[3], hi[3];
  std::fill(lo, lo + 3, std::numeric_limits<double>::infinity());
  std::fill(hi, hi + 3, -std::numeric_limits<double>::infinity());
  for (uint32_t k = begin; k < end; ++k) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], tree.nodes[order[k]].centroid[a]);
      hi[a] = std::max(hi[a], tree.nodes[order[k]].centroid[a]);
    }
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](uint32_t x, uint32_t y) {
                     const double cx = tree.nodes[x].centroid[axis];
                     const double cy = tree.nodes[y].centroid[axis];
                     return cx < cy || (cx == cy && x < y);
                   });
}

// Builds the cluster over order[begin, end) (two or more faces) and those below it.
uint32_t BuildCluster(const ElementTree& tree, ClusterTree& ct, uint32_t begin, uint32_t end,
                      uint32_t parent) {
  const uint32_t index = static_cast<uint32_t>(ct.clusters.size());
  ct.clusters.emplace_back();
  const uint32_t mid = begin + (end - begin) / 2;
  MedianSplit(tree, ct.order, begin, mid, end);
  Cluster c;
  c.begin = begin;
  c.end = end;
  c.parent = parent;
  for (uint32_t k = begin; k < end; ++k) {
    const Element& e = tree.nodes[ct.order[k]];
    c.area += e.area;
    c.center += e.centroid * e.area;
  }
  c.center = c.area > 0 ? c.center / c.area : tree.nodes[ct.order[begin]].centroid;
  for (uint32_t k = begin; k < end; ++k) {
    const Element& e = tree.nodes[ct.order[k]];
    for (int v = 0; v < e.CornerCount(); ++v)
      c.radius = std::max(c.radius, Length(e.corners[v] - c.center));
  }
  const uint32_t ranges[2][2] = {{begin, mid}, {mid, end}};
  for (int h = 0; h < 2; ++h) {
    const auto [b, e] = ranges[h];
    if (e - b == 1) {
      c.children[h] = ct.order[b];
      ct.face_cluster[ct.order[b]] = index;
    } else {
      c.children[h] = kClusterBit | BuildCluster(tree, ct, b, e, index);
    }
  }
  ct.clusters[index] = c;
  return index;
}

}  // namespace

ClusterTree ClusterTree::Build(const ElementTree& tree) {
  ClusterTree ct;
  const uint32_t n = static_cast<uint32_t>(tree.roots.size());
  ct.order = tree.roots;
  ct.face_cluster.assign(n, kNoElement);
  if (n >= 2) BuildCluster(tree, ct, 0, n, kNoElement);
  return ct;
}

double ElementRadius(const Element& e) {
  double r = 0;
  for (int v = 0; v < e.CornerCount(); ++v) r = std::max(r, Length(e.corners[v] - e.centroid));
  return r;
}

}  // namespace radflux
