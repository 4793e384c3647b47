#include "solver/hierarchical/hierarchical_state.h"

#include "solver/core/parallel.h"
#include "solver/hierarchical/exposure.h"

namespace radflux {
namespace {

constexpr int kExposureSamples = 32;
constexpr uint64_t kExposureStream = 14;

}  // namespace

std::vector<uint32_t> Children(const Context& c, const ElementTree& tree, uint32_t node) {
  if (IsCluster(node)) {
    const auto& ch = c.clusters.clusters[ClusterIndex(node)].children;
    return {ch[0], ch[1]};
  }
  const uint32_t first = tree.nodes[node].first_child;
  return {first, first + 1, first + 2, first + 3};
}

void AddNodes(const Context& c, const ElementTree& tree, size_t first, NodeState& state) {
  const size_t n = tree.nodes.size();
  state.b.resize(n);
  state.range.resize(n, 0);
  state.exposure.resize(n, 1);
  for (size_t k = first; k < n; ++k) {
    const Element& e = tree.nodes[k];
    state.b[k] = e.parent == kNoElement ? c.MaterialOf(e).emission : state.b[e.parent];
  }
  ParallelFor(static_cast<int64_t>(n - first), 64, c.threads, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k) {
      const size_t node = first + static_cast<size_t>(k);
      state.exposure[node] = static_cast<float>(ExposedFraction(
          tree.nodes[node], *c.roots, *c.caster, kExposureSamples,
          PatternSeed(c.options->seed, node, kExposureStream), c.sampling.ray_epsilon));
    }
  });
}

Pulled FacePulled(const Rgb& b, double exposed) {
  Pulled p;
  p.exposed = exposed;
  for (int k = 0; k < kBands; ++k) p.b_area[k] = b[k] * exposed;
  if (exposed > 0) p.lo = p.hi = MaxComponent(b);
  return p;
}

void PullClusters(const Context& c, const std::vector<Pulled>& faces, NodeState& state) {
  const std::vector<Cluster>& clusters = c.clusters.clusters;
  std::vector<Pulled> pulled(clusters.size());
  state.cluster_b.resize(clusters.size());
  state.cluster_range.resize(clusters.size());
  for (size_t k = clusters.size(); k-- > 0;) {  // children come after their parent
    for (uint32_t ch : clusters[k].children)
      pulled[k].Add(IsCluster(ch) ? pulled[ClusterIndex(ch)] : faces[ch]);
    const Pulled& p = pulled[k];
    Rgb b{};
    if (p.exposed > 0)
      for (int band = 0; band < kBands; ++band) b[band] = p.b_area[band] / p.exposed;
    state.cluster_b[k] = b;
    state.cluster_range[k] = p.hi > p.lo ? static_cast<float>(p.hi - p.lo) : 0.0f;
  }
}

}  // namespace radflux
