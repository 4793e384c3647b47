#include "solver/hierarchical/hierarchical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "solver/core/parallel.h"
#include "solver/core/seconds_since.h"
#include "solver/formfactor/row_builder.h"
#include "solver/hierarchical/hierarchical_state.h"
#include "solver/hierarchical/link_refine.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux {
namespace {

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
          const double t =
              PointTransfer(links.ff[k], face.centroid, face.normal, c.Center(tree, q));
          for (int band = 0; band < kBands; ++band) g[band] += t * state.B(q)[band];
        }
      }
      for (int band = 0; band < kBands; ++band) gathered[r][band] += g[band] * state.exposure[r];
    }
  });
}

// One gathering sweep (Jacobi over links, then push-pull, then the clusters' pull); returns
// the opaque-area-weighted relative change of B over the leaves, max over bands.
double GatherSweep(const Context& c, const ElementTree& tree, const LinkSet& links,
                   const std::vector<uint32_t>& leaves, const Rgb& e_norm, NodeState& state) {
  std::vector<Rgb> gathered(tree.nodes.size(), Rgb{});
  ParallelFor(static_cast<int64_t>(links.elements), 256, c.threads,
              [&](int64_t begin, int64_t end) {
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
                  faces[root] = FacePulled(state.b[root], exposed * tree.nodes[root].opacity);
                  faces[root].lo = lo;
                  faces[root].hi = hi;
                }
              });
  PullClusters(c, faces, state);
  Rgb diff{};
  for (size_t i = 0; i < leaves.size(); ++i) {
    const double a = tree.nodes[leaves[i]].area * tree.nodes[leaves[i]].opacity;
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
    const double opaque = e.area * e.opacity;  // only the opaque part emits
    power += opaque * MaxComponent(m.emission);
    for (int k = 0; k < kBands; ++k) e_norm[k] += opaque * m.emission[k] * m.emission[k];
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
  for (uint32_t r : tree.roots) {
    const Element& e = tree.nodes[r];
    faces.push_back(FacePulled(state.b[r], e.area * e.opacity * state.exposure[r]));
  }
  PullClusters(c, faces, state);
  LinkSet links = InitialLinks(c, tree, state, stats.rays);
  stats.initial_links = links.size();
  stats.refine_seconds += SecondsSince(start);

  SolveResult& solve = result.solve;
  std::vector<uint32_t> leaves;
  for (int pass = 0; pass < options.max_passes && !solve.cancelled; ++pass) {
    start = std::chrono::steady_clock::now();
    bool changed = false;
    for (int round = 0; round < 64 && RefineRound(c, tree, links, state, stats.rays); ++round) {
      changed = true;
      ++stats.refine_rounds;
    }
    stats.refine_seconds += SecondsSince(start);
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
    stats.solve_seconds += SecondsSince(start);
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
