#include "solver/hierarchical/hierarchical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "solver/core/parallel.h"
#include "solver/formfactor/row_builder.h"
#include "solver/hierarchical/cluster_link.h"
#include "solver/hierarchical/cluster_tree.h"
#include "solver/hierarchical/exposure.h"
#include "solver/hierarchical/link_estimate.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux {
namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct NewLink {
  uint32_t receiver, source;
  float ff = 0, spread = 0;
};

// Everything the refinement and the gather need besides the tree and the links.
struct Context {
  const Scene* scene = nullptr;
  const HierarchicalOptions* options = nullptr;
  const RayCaster* caster = nullptr;
  const PatchMesh* roots = nullptr;  // the mesh `caster` was built on
  ClusterTree clusters;              // empty with clusters off
  std::vector<double> cluster_rho_area;  // per cluster: sum of rho A over its faces (max band)
  LinkSampling sampling;
  double min_area = 0;
  double threshold = 0;  // link_epsilon * emitted power
  int threads = 0;
  const Material& MaterialOf(const Element& e) const {
    return scene->materials[scene->faces[e.face].material];
  }
  // rho A of a node (max band; a cluster: summed over its faces).
  double RhoArea(const ElementTree& tree, uint32_t node) const {
    if (IsCluster(node)) return cluster_rho_area[ClusterIndex(node)];
    const Element& e = tree.nodes[node];
    return MaxComponent(MaterialOf(e).reflectance) * e.area;
  }
  bool CanSplit(const ElementTree& tree, uint32_t node) const {
    return IsCluster(node) || tree.nodes[node].area / 4 >= min_area;
  }
  const Vec3& Center(const ElementTree& tree, uint32_t node) const {
    return IsCluster(node) ? clusters.clusters[ClusterIndex(node)].center : tree.nodes[node].centroid;
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

// The children of a split node: an element's four, or a cluster's two.
std::vector<uint32_t> Children(const Context& c, const ElementTree& tree, uint32_t node) {
  if (IsCluster(node)) {
    const auto& ch = c.clusters.clusters[ClusterIndex(node)].children;
    return {ch[0], ch[1]};
  }
  const uint32_t first = tree.nodes[node].first_child;
  return {first, first + 1, first + 2, first + 3};
}

// Per element: radiosity of its exposed part (what links carry), W/m^2 per band; the range
// of MaxComponent of that over its exposed leaves; its exposed fraction (ExposedFraction).
// Per cluster: the exposed-area mean of its faces' b, and the range over their leaves.
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

// Sets every cluster's b and range from its faces' (`faces`, by root element), bottom-up.
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

// A face's Pulled from its b and an exposed area.
Pulled FacePulled(const Rgb& b, double exposed) {
  Pulled p;
  p.exposed = exposed;
  for (int k = 0; k < kBands; ++k) p.b_area[k] = b[k] * exposed;
  if (exposed > 0) p.lo = p.hi = MaxComponent(b);
  return p;
}

constexpr int kExposureSamples = 32;
constexpr uint64_t kExposureStream = 14;

// State for nodes [first, tree size): their exposure, and their parent's radiosity to start
// from (roots: their emission).
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

// F_pq with its spread for a pending pair; false when p and q cannot exchange or p does not
// reflect. A cluster's link with itself carries nothing (it is always refined).
bool LinkFormFactor(const Context& c, const ElementTree& tree, const NodeState& state,
                    uint32_t p, uint32_t q, NewLink& link, uint64_t& rays) {
  if (!(c.RhoArea(tree, p) > 0)) return false;
  if (p == q && IsCluster(p)) {
    link = {p, q, 0, 1};
    return true;
  }
  LinkEstimate estimate;
  const bool ok =
      IsCluster(p) || IsCluster(q)
          ? EstimateClusterLink(tree, state.exposure, c.End(tree, p), c.End(tree, q), c.sampling,
                                *c.caster, estimate, rays)
          : EstimateElementLink(tree.nodes[p], tree.nodes[q], p, q, c.sampling, *c.caster,
                                estimate, rays);
  if (!ok) return false;
  link = {p, q, estimate.ff, estimate.spread};
  return true;
}

// Computes the form factors of `pending` (receiver, source) pairs in parallel; drops pairs
// that cannot exchange. Deterministic: each pair's samples depend only on (seed, p, q).
std::vector<NewLink> ComputeLinks(const Context& c, const ElementTree& tree,
                                  const NodeState& state,
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
// near, kFarFieldBound) splits its larger end; a
// link between elements the receiver when the receiver part dominates, else the source,
// whichever can still be split.
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
  const bool receiver =
      cluster_end
          ? can_p && (!can_q || c.End(tree, p).radius >= c.End(tree, q).radius)
          : can_p && (error.receiver >= error.source || !can_q);
  if (receiver) return kSplitReceiver;
  return can_q ? kSplitSource : kKeep;
}

// The pairs that replace link p <- q under decision d.
void ReplacementPairs(const Context& c, const ElementTree& tree, uint32_t p, uint32_t q,
                      Decision d, std::vector<std::pair<uint32_t, uint32_t>>& pending) {
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
  // Node ids order elements before clusters, as the slots do.
  std::stable_sort(kept.begin(), kept.end(),
                   [](const NewLink& x, const NewLink& y) { return x.receiver < y.receiver; });
  links = Assemble(c, kept, tree.nodes.size());
  return true;
}

// Push-pull below `p`: `down` is the exposed radiosity gathered by p's ancestors (with rho).
// A node's gathered radiosity is averaged over all its area, so it is divided by the node's
// exposed fraction. Sets state.b (exposed-area-weighted mean over the leaves below) and
// state.range of p and its descendants; returns p's exposed area (sum over its leaves).
double PushPull(const Context& c, const ElementTree& tree, const std::vector<Rgb>& gathered,
                uint32_t p, Rgb down, NodeState& state, double& lo, double& hi) {
  const Element& e = tree.nodes[p];
  const Material& m = c.MaterialOf(e);
  const double exposure = state.exposure[p];
  if (exposure > 0) {
    for (int k = 0; k < kBands; ++k) down[k] += m.reflectance[k] * gathered[p][k] / exposure;
  }
  Rgb result{};
  double exposed = 0;
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  if (e.IsLeaf()) {
    for (int k = 0; k < kBands; ++k) result[k] = m.emission[k] + down[k];
    exposed = e.area * exposure;
    if (exposed > 0) lo = hi = MaxComponent(result);
  } else {
    for (uint32_t ch = e.first_child; ch < e.first_child + 4; ++ch) {
      double child_lo = 0, child_hi = 0;
      const double a = PushPull(c, tree, gathered, ch, down, state, child_lo, child_hi);
      for (int k = 0; k < kBands; ++k) result[k] += state.b[ch][k] * a;
      exposed += a;
      lo = std::min(lo, child_lo);
      hi = std::max(hi, child_hi);
    }
    if (exposed > 0) {
      for (double& v : result) v /= exposed;
    } else {
      result = m.emission;
    }
  }
  state.b[p] = result;
  state.range[p] = hi > lo ? static_cast<float>(hi - lo) : 0.0f;
  return exposed;
}

// The area-weighted mean radiosity of leaf `l` (what the outputs show): zero where buried.
Rgb LeafRadiosity(const NodeState& state, uint32_t l) {
  Rgb b = state.b[l];
  for (double& v : b) v *= state.exposure[l];
  return b;
}

// Adds to each face's gathered radiosity what the clusters holding it gather: per link into
// such a cluster, the face's own PointTransfer toward the source (zero when it faces away)
// times the source's B, times its exposed fraction (gathered is per face area).
void GatherThroughClusters(const Context& c, const ElementTree& tree, const LinkSet& links,
                           const NodeState& state, std::vector<Rgb>& gathered) {
  if (c.clusters.clusters.empty()) return;
  ParallelFor(static_cast<int64_t>(tree.roots.size()), 64, c.threads, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) {
      const uint32_t r = tree.roots[i];
      const Element& face = tree.nodes[r];
      Rgb g{};
      for (uint32_t a = c.clusters.face_cluster[r]; a != kNoElement;
           a = c.clusters.clusters[a].parent) {
        const size_t slot = links.elements + a;
        for (uint64_t k = links.begin[slot]; k < links.begin[slot + 1]; ++k) {
          const uint32_t q = links.source[k];
          const double t = PointTransfer(links.ff[k], face.centroid, face.normal, c.Center(tree, q));
          for (int band = 0; band < kBands; ++band) g[band] += t * state.B(q)[band];
        }
      }
      for (int band = 0; band < kBands; ++band) gathered[r][band] += g[band] * state.exposure[r];
    }
  });
}

// One gathering sweep (Jacobi over links, then push-pull, then the clusters' pull); returns
// the area-weighted relative change of B over the leaves, max over bands.
double GatherSweep(const Context& c, const ElementTree& tree, const LinkSet& links,
                   const std::vector<uint32_t>& leaves, const Rgb& e_norm, NodeState& state) {
  std::vector<Rgb> gathered(tree.nodes.size(), Rgb{});
  ParallelFor(static_cast<int64_t>(links.elements), 256, c.threads, [&](int64_t begin, int64_t end) {
    for (int64_t p = begin; p < end; ++p) {
      Rgb g{};
      for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
        const Rgb& bq = state.B(links.source[k]);
        for (int band = 0; band < kBands; ++band) g[band] += links.ff[k] * bq[band];
      }
      gathered[p] = g;
    }
  });
  GatherThroughClusters(c, tree, links, state, gathered);
  std::vector<Rgb> old(leaves.size());
  for (size_t i = 0; i < leaves.size(); ++i) old[i] = LeafRadiosity(state, leaves[i]);
  std::vector<Pulled> faces(tree.roots.size());
  ParallelFor(static_cast<int64_t>(tree.roots.size()), 16, c.threads,
              [&](int64_t begin, int64_t end) {
                for (int64_t r = begin; r < end; ++r) {
                  double lo = 0, hi = 0;
                  const uint32_t root = tree.roots[r];
                  const double exposed = PushPull(c, tree, gathered, root, Rgb{}, state, lo, hi);
                  faces[root] = FacePulled(state.b[root], exposed);
                  faces[root].lo = lo;
                  faces[root].hi = hi;
                }
              });
  PullClusters(c, faces, state);
  Rgb diff{};
  for (size_t i = 0; i < leaves.size(); ++i) {
    const double a = tree.nodes[leaves[i]].area;
    for (int k = 0; k < kBands; ++k) {
      const double d = LeafRadiosity(state, leaves[i])[k] - old[i][k];
      diff[k] += a * d * d;
    }
  }
  double worst = 0;
  for (int k = 0; k < kBands; ++k)
    if (e_norm[k] > 0) worst = std::max(worst, std::sqrt(diff[k]) / e_norm[k]);
  return worst;
}

}  // namespace

absl::StatusOr<HierarchicalResult> SolveHierarchical(const Scene& scene,
                                                     const HierarchicalOptions& options,
                                                     const SolverOptions& solver,
                                                     const SolveCallback& callback) {
  if (!(options.link_epsilon > 0) || !(options.min_area_fraction > 0) || options.samples < 1) {
    return absl::InvalidArgumentError(
        "hierarchical: --link-epsilon, min area fraction and samples must be > 0");
  }
  absl::StatusOr<PatchMesh> roots = SubdivideScene(scene, MeshOptions{});
  if (!roots.ok()) return roots.status();
  absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> caster = EmbreeRayCaster::Create(*roots);
  if (!caster.ok()) return caster.status();

  HierarchicalResult result;
  result.tree = ElementTree::FromMesh(*roots);
  ElementTree& tree = result.tree;
  Context c;
  c.scene = &scene;
  c.options = &options;
  c.caster = caster->get();
  c.roots = &*roots;
  c.sampling.samples = options.samples;
  c.sampling.seed = options.seed;
  c.sampling.ray_epsilon = RayEpsilonFor(*roots);
  c.threads = solver.threads;
  double total_area = 0, power = 0;
  Rgb e_norm{};
  for (const Element& e : tree.nodes) {
    const Material& m = c.MaterialOf(e);
    total_area += e.area;
    power += e.area * MaxComponent(m.emission);
    for (int k = 0; k < kBands; ++k) e_norm[k] += e.area * m.emission[k] * m.emission[k];
  }
  for (double& v : e_norm) v = std::sqrt(v);
  c.min_area = options.min_area_fraction * total_area;
  c.threshold = options.link_epsilon * power;
  if (options.clusters) c.clusters = ClusterTree::Build(tree);
  for (const Cluster& cl : c.clusters.clusters) {
    double rho_a = 0;
    for (uint32_t k = cl.begin; k < cl.end; ++k) rho_a += c.RhoArea(tree, c.clusters.order[k]);
    c.cluster_rho_area.push_back(rho_a);
  }

  HierarchicalStats& stats = result.stats;
  auto start = std::chrono::steady_clock::now();
  NodeState state;
  AddNodes(c, tree, 0, state);
  std::vector<Pulled> faces;
  for (uint32_t r : tree.roots)
    faces.push_back(FacePulled(state.b[r], tree.nodes[r].area * state.exposure[r]));
  PullClusters(c, faces, state);
  LinkSet links = InitialLinks(c, tree, state, stats.rays);
  stats.initial_links = links.size();
  stats.refine_seconds += Seconds(start);

  SolveResult& solve = result.solve;
  std::vector<uint32_t> leaves;
  for (int pass = 0; pass < options.max_passes && !solve.cancelled; ++pass) {
    start = std::chrono::steady_clock::now();
    bool changed = false;
    for (int round = 0; round < 64 && RefineRound(c, tree, links, state, stats.rays); ++round) {
      changed = true;
      ++stats.refine_rounds;
    }
    stats.refine_seconds += Seconds(start);
    if (pass > 0 && !changed) break;
    ++stats.passes;
    start = std::chrono::steady_clock::now();
    leaves = tree.Leaves();
    solve.converged = false;
    for (int it = 0; it < solver.max_iterations; ++it) {
      if (solver.cancel && solver.cancel->load()) {
        solve.cancelled = true;
        break;
      }
      const double change = GatherSweep(c, tree, links, leaves, e_norm, state);
      ++solve.iterations;
      solve.residual_history.push_back(change);
      solve.residual = change;
      if (callback) {
        SolveProgress progress;
        progress.iteration = solve.iterations;
        progress.residual = change;
        std::vector<Rgb> snapshot;
        if (solver.snapshot_every > 0 && solve.iterations % solver.snapshot_every == 0) {
          for (uint32_t l : leaves) snapshot.push_back(LeafRadiosity(state, l));
          progress.snapshot = &snapshot;
          progress.state = &snapshot;
        }
        callback(progress);
      }
      if (change <= solver.tolerance) {
        solve.converged = true;
        break;
      }
    }
    stats.solve_seconds += Seconds(start);
  }
  result.leaves = tree.Leaves();
  for (uint32_t l : result.leaves) result.leaf_radiosity.push_back(LeafRadiosity(state, l));
  result.mesh = BuildLeafMesh(tree, result.leaves, /*conforming=*/true, &result.patch_leaf);
  solve.radiosity.resize(result.mesh.size());
  for (size_t p = 0; p < result.mesh.size(); ++p)
    solve.radiosity[p] = result.leaf_radiosity[result.patch_leaf[p]];
  bool grey = true;
  for (const Material& m : scene.materials)
    grey = grey && IsGrey(m.reflectance) && IsGrey(m.emission);
  solve.bands_solved = grey ? 1 : kBands;

  stats.roots = tree.roots.size();
  stats.clusters = c.clusters.clusters.size();
  stats.elements = tree.nodes.size();
  stats.leaves = result.leaves.size();
  stats.links = links.size();
  stats.link_bytes = links.Bytes();
  stats.element_bytes = tree.nodes.size() * sizeof(Element);
  stats.patches = result.mesh.size();
  result.links = std::move(links);
  return result;
}

}  // namespace radflux
