#include "solver/hierarchical/hierarchical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "solver/core/parallel.h"
#include "solver/formfactor/row_builder.h"
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
  LinkSampling sampling;
  double min_area = 0;
  double threshold = 0;  // link_epsilon * emitted power
  int threads = 0;
  const Material& MaterialOf(const Element& e) const {
    return scene->materials[scene->faces[e.face].material];
  }
};

// Per element: radiosity of its exposed part (what links carry), W/m^2 per band; the range
// of MaxComponent of that over its exposed leaves; its exposed fraction (ExposedFraction).
struct NodeState {
  std::vector<Rgb> b;
  std::vector<float> range;
  std::vector<float> exposure;
};

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

// F_pq with its spread for a pending pair; false when p and q cannot exchange.
bool LinkFormFactor(const Context& c, const ElementTree& tree, uint32_t p, uint32_t q,
                    NewLink& link, uint64_t& rays) {
  LinkEstimate estimate;
  if (!EstimateElementLink(tree.nodes[p], tree.nodes[q], p, q, c.sampling, *c.caster, estimate,
                           rays)) {
    return false;
  }
  link = {p, q, estimate.ff, estimate.spread};
  return true;
}

// Computes the form factors of `pending` (receiver, source) pairs in parallel; drops pairs
// that cannot exchange. Deterministic: each pair's samples depend only on (seed, p, q).
std::vector<NewLink> ComputeLinks(const Context& c, const ElementTree& tree,
                                  const std::vector<std::pair<uint32_t, uint32_t>>& pending,
                                  uint64_t& rays) {
  std::vector<NewLink> links(pending.size());
  std::vector<uint8_t> ok(pending.size(), 0);
  std::vector<uint64_t> block_rays((pending.size() + 255) / 256, 0);
  ParallelFor(static_cast<int64_t>(pending.size()), 256, c.threads, [&](int64_t b, int64_t e) {
    uint64_t r = 0;
    for (int64_t k = b; k < e; ++k) {
      ok[k] = LinkFormFactor(c, tree, pending[k].first, pending[k].second, links[k], r);
    }
    block_rays[b / 256] = r;
  });
  for (uint64_t r : block_rays) rays += r;
  std::vector<NewLink> kept;
  for (size_t k = 0; k < links.size(); ++k)
    if (ok[k]) kept.push_back(links[k]);
  return kept;
}

// Links grouped by receiver, keeping the given order within a receiver.
LinkSet Assemble(const std::vector<NewLink>& links, size_t nodes) {
  LinkSet set;
  set.begin.assign(nodes + 1, 0);
  for (const NewLink& l : links) ++set.begin[l.receiver + 1];
  for (size_t p = 0; p < nodes; ++p) set.begin[p + 1] += set.begin[p];
  std::vector<uint64_t> next(set.begin.begin(), set.begin.end() - 1);
  set.source.resize(links.size());
  set.ff.resize(links.size());
  set.spread.resize(links.size());
  for (const NewLink& l : links) {
    const uint64_t k = next[l.receiver]++;
    set.source[k] = l.source;
    set.ff[k] = l.ff;
    set.spread[k] = l.spread;
  }
  return set;
}

bool NeedsLight(const Context& c, const Element& e) {
  return MaxComponent(c.MaterialOf(e).reflectance) > 0;
}

LinkSet InitialLinks(const Context& c, const ElementTree& tree, uint64_t& rays) {
  std::vector<std::pair<uint32_t, uint32_t>> pending;
  for (uint32_t p : tree.roots) {
    if (!NeedsLight(c, tree.nodes[p])) continue;
    for (uint32_t q : tree.roots)
      if (q != p) pending.push_back({p, q});
  }
  return Assemble(ComputeLinks(c, tree, pending, rays), tree.nodes.size());
}

enum Decision : uint8_t { kKeep = 0, kSplitReceiver = 1, kSplitSource = 2 };

// The error of link p <- q in power: the receiver part (q's radiosity times how much F_pq
// varies over p, which p's single value misses) plus the source part (F_pq times how much B
// varies over q's leaves, which q's mean misses); both times rho_p A_p.
struct LinkError {
  double receiver = 0, source = 0;
  double Total() const { return receiver + source; }
};

// One refinement round: every link over threshold splits one side (one level): the receiver
// when the receiver part dominates, else the source, whichever can still be split.
// Returns true when any link was refined.
bool RefineRound(const Context& c, ElementTree& tree, LinkSet& links, NodeState& state,
                 uint64_t& rays) {
  const size_t nodes = tree.nodes.size();
  std::vector<uint8_t> decision(links.size(), kKeep);
  ParallelFor(static_cast<int64_t>(nodes), 256, c.threads, [&](int64_t begin, int64_t end) {
    for (int64_t p = begin; p < end; ++p) {
      const Element& ep = tree.nodes[p];
      const double rho_a = MaxComponent(c.MaterialOf(ep).reflectance) * ep.area;
      for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
        const uint32_t q = links.source[k];
        const LinkError error{rho_a * MaxComponent(state.b[q]) * links.spread[k],
                              rho_a * links.ff[k] * state.range[q]};
        if (!(error.Total() > c.threshold)) continue;
        const bool can_p = ep.area / 4 >= c.min_area;
        const bool can_q = tree.nodes[q].area / 4 >= c.min_area;
        if (can_p && (error.receiver >= error.source || !can_q)) {
          decision[k] = kSplitReceiver;
        } else if (can_q) {
          decision[k] = kSplitSource;
        }
      }
    }
  });
  bool any = false;
  for (size_t p = 0; p < nodes; ++p) {
    for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
      if (decision[k] == kKeep) continue;
      any = true;
      const uint32_t n = decision[k] == kSplitReceiver ? static_cast<uint32_t>(p) : links.source[k];
      if (tree.nodes[n].IsLeaf()) tree.Split(n);
    }
  }
  if (!any) return false;
  AddNodes(c, tree, nodes, state);
  std::vector<NewLink> kept;
  std::vector<std::pair<uint32_t, uint32_t>> pending;
  for (size_t p = 0; p < nodes; ++p) {
    for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
      const uint32_t q = links.source[k];
      if (decision[k] == kKeep) {
        kept.push_back({static_cast<uint32_t>(p), q, links.ff[k], links.spread[k]});
      } else if (decision[k] == kSplitReceiver) {
        const uint32_t first = tree.nodes[p].first_child;
        for (uint32_t ch = first; ch < first + 4; ++ch) pending.push_back({ch, q});
      } else {
        const uint32_t first = tree.nodes[q].first_child;
        for (uint32_t ch = first; ch < first + 4; ++ch)
          pending.push_back({static_cast<uint32_t>(p), ch});
      }
    }
  }
  std::vector<NewLink> fresh = ComputeLinks(c, tree, pending, rays);
  kept.insert(kept.end(), fresh.begin(), fresh.end());
  std::stable_sort(kept.begin(), kept.end(),
                   [](const NewLink& x, const NewLink& y) { return x.receiver < y.receiver; });
  links = Assemble(kept, tree.nodes.size());
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

// One gathering sweep (Jacobi over links, then push-pull); returns the area-weighted
// relative change of B over the leaves, max over bands.
double GatherSweep(const Context& c, const ElementTree& tree, const LinkSet& links,
                   const std::vector<uint32_t>& leaves, const Rgb& e_norm, NodeState& state) {
  const size_t nodes = tree.nodes.size();
  std::vector<Rgb> gathered(nodes, Rgb{});
  ParallelFor(static_cast<int64_t>(nodes), 256, c.threads, [&](int64_t begin, int64_t end) {
    for (int64_t p = begin; p < end; ++p) {
      Rgb g{};
      for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
        const Rgb& bq = state.b[links.source[k]];
        for (int band = 0; band < kBands; ++band) g[band] += links.ff[k] * bq[band];
      }
      gathered[p] = g;
    }
  });
  std::vector<Rgb> old(leaves.size());
  for (size_t i = 0; i < leaves.size(); ++i) old[i] = LeafRadiosity(state, leaves[i]);
  ParallelFor(static_cast<int64_t>(tree.roots.size()), 16, c.threads,
              [&](int64_t begin, int64_t end) {
                for (int64_t r = begin; r < end; ++r) {
                  double lo = 0, hi = 0;
                  PushPull(c, tree, gathered, tree.roots[r], Rgb{}, state, lo, hi);
                }
              });
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

  HierarchicalStats& stats = result.stats;
  auto start = std::chrono::steady_clock::now();
  LinkSet links = InitialLinks(c, tree, stats.rays);
  stats.refine_seconds += Seconds(start);
  NodeState state;
  AddNodes(c, tree, 0, state);

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
