// The state hierarchical radiosity keeps besides the element tree and the links: what the
// refinement and the gather share (Context), B, its range and the exposed fraction per node
// (NodeState), and the clusters' pull of B from their faces. Internal to solver/hierarchical.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "solver/hierarchical/cluster_link.h"
#include "solver/hierarchical/cluster_tree.h"
#include "solver/hierarchical/hierarchical.h"
#include "solver/hierarchical/link_estimate.h"

namespace radflux {

// A link p <- q before it is placed in a LinkSet (see LinkSet for ff and spread).
struct NewLink {
  uint32_t receiver, source;
  float ff = 0, spread = 0;
};

// Everything the refinement and the gather need besides the tree and the links.
struct Context {
  const Scene* scene = nullptr;
  const HierarchicalOptions* options = nullptr;
  const RayCaster* caster = nullptr;
  const PatchMesh* roots = nullptr;      // the mesh `caster` was built on
  ClusterTree clusters;                  // empty with clusters off
  std::vector<double> cluster_rho_area;  // per cluster: sum of rho A over its faces (max band)
  LinkSampling sampling;
  double min_area = 0;
  double threshold = 0;  // link_epsilon * emitted power
  int threads = 0;
  const Material& MaterialOf(const Element& e) const {
    return scene->materials[scene->faces[e.face].material];
  }
  // rho A of a node's opaque part, what it reflects per unit of gathered radiosity (max
  // band; a cluster: summed over its faces).
  double RhoArea(const ElementTree& tree, uint32_t node) const {
    if (IsCluster(node)) return cluster_rho_area[ClusterIndex(node)];
    const Element& e = tree.nodes[node];
    return MaxComponent(MaterialOf(e).reflectance) * e.area * e.opacity;
  }
  bool CanSplit(const ElementTree& tree, uint32_t node) const {
    return IsCluster(node) || tree.nodes[node].area / 4 >= min_area;
  }
  const Vec3& Center(const ElementTree& tree, uint32_t node) const {
    return IsCluster(node) ? clusters.clusters[ClusterIndex(node)].center
                           : tree.nodes[node].centroid;
  }
  LinkEnd End(const ElementTree& tree, uint32_t node) const {
    if (!IsCluster(node)) {
      const Element& e = tree.nodes[node];
      return {node, e.centroid, ElementRadius(e), e.area, {}};
    }
    const Cluster& cl = clusters.clusters[ClusterIndex(node)];
    return {node, cl.center, cl.radius, cl.area,
            std::span<const uint32_t>(clusters.order).subspan(cl.begin, cl.end - cl.begin)};
  }
};

// Per element: radiosity of its exposed part (what links carry), W/m^2 per band; the range
// of MaxComponent of that over its exposed leaves; its exposed fraction (ExposedFraction).
// Per cluster: the mean of its faces' b weighted by their exposed opaque area (what each
// sends), and the range over their leaves.
struct NodeState {
  std::vector<Rgb> b;
  std::vector<float> range;
  std::vector<float> exposure;
  std::vector<Rgb> cluster_b;
  std::vector<float> cluster_range;
  const Rgb& B(uint32_t node) const {
    return IsCluster(node) ? cluster_b[ClusterIndex(node)] : b[node];
  }
  float Range(uint32_t node) const {
    return IsCluster(node) ? cluster_range[ClusterIndex(node)] : range[node];
  }
};

// The children of a split node: an element's four, or a cluster's two.
std::vector<uint32_t> Children(const Context& c, const ElementTree& tree, uint32_t node);

// State for nodes [first, tree size): their exposure, and their parent's radiosity to start
// from (roots: their emission).
void AddNodes(const Context& c, const ElementTree& tree, size_t first, NodeState& state);

// What a cluster pulls from a face or a sub-cluster: b times exposed area, the exposed area,
// and the least and greatest MaxComponent of B over its exposed leaves (inf, -inf if none).
struct Pulled {
  Rgb b_area{};
  double exposed = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  void Add(const Pulled& o) {
    for (int k = 0; k < kBands; ++k) b_area[k] += o.b_area[k];
    exposed += o.exposed;
    lo = std::min(lo, o.lo);
    hi = std::max(hi, o.hi);
  }
};

// A face's Pulled from its b and its exposed opaque area (exposed area times opacity).
Pulled FacePulled(const Rgb& b, double exposed);

// Sets every cluster's b and range from its faces' (`faces`, by root element), bottom-up.
void PullClusters(const Context& c, const std::vector<Pulled>& faces, NodeState& state);

}  // namespace radflux
