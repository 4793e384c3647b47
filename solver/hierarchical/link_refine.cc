#include "solver/hierarchical/link_refine.h"

#include <algorithm>
#include <utility>

#include "solver/core/parallel.h"

namespace radflux {
namespace {

// F_pq with its spread for a pending pair; false when p and q cannot exchange or p does not
// reflect. A cluster's link with itself carries nothing (it is always refined).
bool LinkFormFactor(const Context& c, const ElementTree& tree, const NodeState& state, uint32_t p,
                    uint32_t q, NewLink& link, uint64_t& rays) {
  if (!(c.RhoArea(tree, p) > 0)) return false;
  if (p == q && IsCluster(p)) {
    link = {p, q, 0, 1};
    return true;
  }
  LinkEstimate estimate;
  const bool ok = IsCluster(p) || IsCluster(q)
                      ? EstimateClusterLink(tree, state.exposure, c.End(tree, p), c.End(tree, q),
                                            c.sampling, *c.caster, estimate, rays)
                      : EstimateElementLink(tree.nodes[p], tree.nodes[q], p, q, c.sampling,
                                            *c.caster, estimate, rays);
  if (!ok) return false;
  link = {p, q, estimate.ff, estimate.spread};
  return true;
}

// Computes the form factors of `pending` (receiver, source) pairs in parallel; drops pairs
// that cannot exchange. Deterministic: each pair's samples depend only on (seed, p, q).
std::vector<NewLink> ComputeLinks(const Context& c, const ElementTree& tree, const NodeState& state,
                                  const std::vector<std::pair<uint32_t, uint32_t>>& pending,
                                  uint64_t& rays) {
  std::vector<NewLink> links(pending.size());
  std::vector<uint8_t> ok(pending.size(), 0);
  std::vector<uint64_t> block_rays((pending.size() + 255) / 256, 0);
  ParallelFor(static_cast<int64_t>(pending.size()), 256, c.threads, [&](int64_t b, int64_t e) {
    uint64_t r = 0;
    for (int64_t k = b; k < e; ++k) {
      ok[k] = LinkFormFactor(c, tree, state, pending[k].first, pending[k].second, links[k], r);
    }
    block_rays[b / 256] = r;
  });
  for (uint64_t r : block_rays) rays += r;
  std::vector<NewLink> kept;
  for (size_t k = 0; k < links.size(); ++k)
    if (ok[k]) kept.push_back(links[k]);
  return kept;
}

// Links grouped by receiver slot (elements, then clusters), keeping the given order within a
// receiver.
LinkSet Assemble(const Context& c, const std::vector<NewLink>& links, size_t elements) {
  LinkSet set;
  set.elements = static_cast<uint32_t>(elements);
  const size_t slots = elements + c.clusters.clusters.size();
  auto slot = [&](uint32_t node) { return IsCluster(node) ? elements + ClusterIndex(node) : node; };
  set.begin.assign(slots + 1, 0);
  for (const NewLink& l : links) ++set.begin[slot(l.receiver) + 1];
  for (size_t p = 0; p < slots; ++p) set.begin[p + 1] += set.begin[p];
  std::vector<uint64_t> next(set.begin.begin(), set.begin.end() - 1);
  set.source.resize(links.size());
  set.ff.resize(links.size());
  set.spread.resize(links.size());
  for (const NewLink& l : links) {
    const uint64_t k = next[slot(l.receiver)]++;
    set.source[k] = l.source;
    set.ff[k] = l.ff;
    set.spread[k] = l.spread;
  }
  return set;
}

// A link with a cluster end is refined, whatever its error, while its form-factor bound is
// above this: its estimate sees faces from afar, which holds only for a small solid angle.
// (Before the first solve most B are zero, and such links would otherwise stay.)
constexpr double kFarFieldBound = 0.3;

enum Decision : uint8_t { kKeep = 0, kSplitReceiver = 1, kSplitSource = 2, kSplitBoth = 3 };

// The error of link p <- q in power: the receiver part (q's radiosity times how much F_pq
// varies over p, which p's single value misses) plus the source part (F_pq times how much B
// varies over q's leaves, which q's mean misses); both times rho_p A_p.
struct LinkError {
  double receiver = 0, source = 0;
  double Total() const { return receiver + source; }
};

// The decision for link k (p <- q) over threshold or not: a cluster's link with itself is
// always split into its children's links; a link with a cluster end (refined also while
// near, kFarFieldBound) splits the larger of two clusters (bounding sphere), or the cluster
// when the other end is an element (opening the cluster leads to links between elements,
// where EstimateElementLink's spread takes over; splitting the element instead would
// multiply the links of every cluster it sees); a link between elements splits the receiver
// when the receiver part dominates, else the source, whichever can still be split.
Decision Decide(const Context& c, const ElementTree& tree, const LinkSet& links,
                const NodeState& state, uint32_t p, uint64_t k) {
  const uint32_t q = links.source[k];
  if (p == q) return kSplitBoth;
  const bool cluster_end = IsCluster(p) || IsCluster(q);
  const double rho_a = c.RhoArea(tree, p);
  const double f = IsCluster(p) ? links.spread[k] : links.ff[k];  // ff is k for a cluster p
  const LinkError error{rho_a * MaxComponent(state.B(q)) * links.spread[k],
                        rho_a * f * state.Range(q)};
  const bool near = cluster_end && links.spread[k] > kFarFieldBound;
  if (!near && !(error.Total() > c.threshold)) return kKeep;
  const bool can_p = c.CanSplit(tree, p), can_q = c.CanSplit(tree, q);
  bool receiver = can_p && (error.receiver >= error.source || !can_q);
  if (IsCluster(p) && IsCluster(q)) {
    receiver = c.End(tree, p).radius >= c.End(tree, q).radius;
  } else if (cluster_end) {
    receiver = IsCluster(p);
  }
  if (receiver) return kSplitReceiver;
  return can_q ? kSplitSource : kKeep;
}

// The pairs that replace link p <- q under decision d.
void ReplacementPairs(const Context& c, const ElementTree& tree, uint32_t p, uint32_t q, Decision d,
                      std::vector<std::pair<uint32_t, uint32_t>>& pending) {
  if (d == kSplitReceiver) {
    for (uint32_t ch : Children(c, tree, p)) pending.push_back({ch, q});
  } else if (d == kSplitSource) {
    for (uint32_t ch : Children(c, tree, q)) pending.push_back({p, ch});
  } else {
    const std::vector<uint32_t> children = Children(c, tree, p);
    for (uint32_t a : children)
      for (uint32_t b : children) pending.push_back({a, b});
  }
}

}  // namespace

// The top cluster's link with itself, or without clusters every ordered pair of faces.
LinkSet InitialLinks(const Context& c, const ElementTree& tree, const NodeState& state,
                     uint64_t& rays) {
  std::vector<std::pair<uint32_t, uint32_t>> pending;
  if (!c.clusters.clusters.empty()) {
    pending.push_back({kClusterBit, kClusterBit});
  } else {
    for (uint32_t p : tree.roots)
      for (uint32_t q : tree.roots)
        if (q != p) pending.push_back({p, q});
  }
  return Assemble(c, ComputeLinks(c, tree, state, pending, rays), tree.nodes.size());
}

// One refinement round: every link over threshold (and every cluster's link with itself) is
// replaced by its children's links, one level down (Decide). Returns true when any link was.
bool RefineRound(const Context& c, ElementTree& tree, LinkSet& links, NodeState& state,
                 uint64_t& rays) {
  const size_t nodes = tree.nodes.size();
  std::vector<uint8_t> decision(links.size(), kKeep);
  ParallelFor(static_cast<int64_t>(links.Slots()), 256, c.threads, [&](int64_t begin, int64_t end) {
    for (int64_t s = begin; s < end; ++s) {
      const uint32_t p = links.Receiver(s);
      for (uint64_t k = links.begin[s]; k < links.begin[s + 1]; ++k)
        decision[k] = Decide(c, tree, links, state, p, k);
    }
  });
  bool any = false;
  for (size_t s = 0; s < links.Slots(); ++s) {
    for (uint64_t k = links.begin[s]; k < links.begin[s + 1]; ++k) {
      if (decision[k] == kKeep) continue;
      any = true;
      const uint32_t n = decision[k] == kSplitSource ? links.source[k] : links.Receiver(s);
      if (!IsCluster(n) && tree.nodes[n].IsLeaf()) tree.Split(n);
    }
  }
  if (!any) return false;
  AddNodes(c, tree, nodes, state);
  std::vector<NewLink> kept;
  std::vector<std::pair<uint32_t, uint32_t>> pending;
  for (size_t s = 0; s < links.Slots(); ++s) {
    const uint32_t p = links.Receiver(s);
    for (uint64_t k = links.begin[s]; k < links.begin[s + 1]; ++k) {
      const uint32_t q = links.source[k];
      if (decision[k] == kKeep) {
        kept.push_back({p, q, links.ff[k], links.spread[k]});
      } else {
        ReplacementPairs(c, tree, p, q, static_cast<Decision>(decision[k]), pending);
      }
    }
  }
  std::vector<NewLink> fresh = ComputeLinks(c, tree, state, pending, rays);
  kept.insert(kept.end(), fresh.begin(), fresh.end());
  links = Assemble(c, kept, tree.nodes.size());  // a stable counting sort by receiver
  return true;
}

}  // namespace radflux
