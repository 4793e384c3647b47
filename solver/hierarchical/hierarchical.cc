#include "solver/hierarchical/hierarchical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "solver/core/parallel.h"
#include "solver/formfactor/polygon_form_factor.h"
#include "solver/formfactor/row_builder.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux {
namespace {

constexpr uint64_t kPointStream = 11;
constexpr uint64_t kTargetStream = 12;
constexpr int kNearFactor = 16;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct NewLink {
  uint32_t receiver, source;
  float ff = 0, bound = 0;
};

// Everything the refinement and the gather need besides the tree and the links.
struct Context {
  const Scene* scene = nullptr;
  const HierarchicalOptions* options = nullptr;
  const RayCaster* caster = nullptr;
  double ray_epsilon = 0;
  double min_area = 0;
  double threshold = 0;  // link_epsilon * emitted power
  int threads = 0;
  const Material& MaterialOf(const Element& e) const {
    return scene->materials[scene->faces[e.face].material];
  }
};

bool AnyCornerInFront(const Element& of, const Element& plane) {
  const double scale = std::sqrt(plane.area);
  for (int k = 0; k < of.CornerCount(); ++k) {
    if (Dot(of.corners[k] - plane.centroid, plane.normal) > 1e-9 * scale) return true;
  }
  return false;
}

// F_pq at `samples` points of p with one shadow ray each; false when p and q cannot exchange.
bool LinkFormFactor(const Context& c, const ElementTree& tree, uint32_t p, uint32_t q,
                    NewLink& link, uint64_t& rays) {
  const Element& ep = tree.nodes[p];
  const Element& eq = tree.nodes[q];
  if (p == q || !AnyCornerInFront(eq, ep) || !AnyCornerInFront(ep, eq)) return false;
  const std::vector<Vec3> polygon = ClipPolygonToHalfSpace(ElementPolygon(eq), ep.centroid,
                                                           ep.normal);
  if (polygon.size() < 3) return false;
  // Near pairs (within about one element size) have a near-singular kernel over p: point
  // sampling needs many more points there for the links of one leaf to sum close to 1.
  const double size = std::sqrt(std::max(ep.area, eq.area));
  const bool near = Length(ep.centroid - eq.centroid) < 1.5 * size;
  const int s = c.options->samples * (near ? kNearFactor : 1);
  const uint64_t seed = c.options->seed;
  const uint32_t point_pattern = PatternSeed(seed, p, kPointStream);
  const uint32_t target_pattern = PatternSeed(seed ^ (uint64_t{p} << 32), q, kTargetStream);
  double seen = 0, unoccluded = 0;
  int visible = 0, blocked = 0;
  for (int m = 0; m < s; ++m) {
    const Vec3 x = SampleElementPoint(ep, MultiJitteredSample(m, s, point_pattern));
    const double f = UnclippedPointToPolygonFormFactor(x, ep.normal, polygon);
    if (f <= 0) continue;
    unoccluded += f;
    const Vec3 y = SampleElementPoint(eq, MultiJitteredSample(m, s, target_pattern)) +
                   eq.normal * c.ray_epsilon;
    const Vec3 origin = x + ep.normal * c.ray_epsilon;
    ++rays;
    if (c.caster->Occluded({origin, y - origin, 0, 1 - 1e-6})) {
      ++blocked;
    } else {
      ++visible;
      seen += f;
    }
  }
  if (unoccluded <= 0) return false;
  link.receiver = p;
  link.source = q;
  link.ff = static_cast<float>(seen / s);
  link.bound = static_cast<float>((visible > 0 && blocked > 0 ? unoccluded : seen) / s);
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
  set.bound.resize(links.size());
  for (const NewLink& l : links) {
    const uint64_t k = next[l.receiver]++;
    set.source[k] = l.source;
    set.ff[k] = l.ff;
    set.bound[k] = l.bound;
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

// One refinement round: every link over threshold splits its larger element (one level).
// Returns true when any link was refined.
bool RefineRound(const Context& c, ElementTree& tree, LinkSet& links, std::vector<Rgb>& b,
                 uint64_t& rays) {
  const size_t nodes = tree.nodes.size();
  std::vector<uint8_t> decision(links.size(), kKeep);
  ParallelFor(static_cast<int64_t>(nodes), 256, c.threads, [&](int64_t begin, int64_t end) {
    for (int64_t p = begin; p < end; ++p) {
      const Element& ep = tree.nodes[p];
      const double rho = MaxComponent(c.MaterialOf(ep).reflectance);
      for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
        const Element& eq = tree.nodes[links.source[k]];
        const double error = rho * MaxComponent(b[links.source[k]]) * links.bound[k] * ep.area;
        if (!(error > c.threshold)) continue;
        const bool can_p = ep.area / 4 >= c.min_area, can_q = eq.area / 4 >= c.min_area;
        if (can_p && (ep.area >= eq.area || !can_q)) {
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
      if (tree.nodes[n].IsLeaf()) {
        const uint32_t first = tree.Split(n);
        b.resize(tree.nodes.size());
        for (int ch = 0; ch < 4; ++ch) b[first + ch] = b[n];
      }
    }
  }
  if (!any) return false;
  std::vector<NewLink> kept;
  std::vector<std::pair<uint32_t, uint32_t>> pending;
  for (size_t p = 0; p < nodes; ++p) {
    for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
      const uint32_t q = links.source[k];
      if (decision[k] == kKeep) {
        kept.push_back({static_cast<uint32_t>(p), q, links.ff[k], links.bound[k]});
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
  std::stable_sort(kept.begin(), kept.end(), [](const NewLink& x, const NewLink& y) {
    return x.receiver < y.receiver;
  });
  links = Assemble(kept, tree.nodes.size());
  return true;
}

// Push-pull below `p`: `down` is the radiosity gathered by p's ancestors (with rho).
Rgb PushPull(const Context& c, const ElementTree& tree, const std::vector<Rgb>& gathered,
             uint32_t p, Rgb down, std::vector<Rgb>& b) {
  const Element& e = tree.nodes[p];
  const Material& m = c.MaterialOf(e);
  for (int k = 0; k < kBands; ++k) down[k] += m.reflectance[k] * gathered[p][k];
  Rgb result{};
  if (e.IsLeaf()) {
    for (int k = 0; k < kBands; ++k) result[k] = m.emission[k] + down[k];
  } else {
    for (uint32_t ch = e.first_child; ch < e.first_child + 4; ++ch) {
      const Rgb child = PushPull(c, tree, gathered, ch, down, b);
      for (int k = 0; k < kBands; ++k) result[k] += child[k] * tree.nodes[ch].area / e.area;
    }
  }
  b[p] = result;
  return result;
}

// One gathering sweep (Jacobi over links, then push-pull); returns the area-weighted
// relative change of B over the leaves, max over bands.
double GatherSweep(const Context& c, const ElementTree& tree, const LinkSet& links,
                   const std::vector<uint32_t>& leaves, const Rgb& e_norm, std::vector<Rgb>& b) {
  const size_t nodes = tree.nodes.size();
  std::vector<Rgb> gathered(nodes, Rgb{});
  ParallelFor(static_cast<int64_t>(nodes), 256, c.threads, [&](int64_t begin, int64_t end) {
    for (int64_t p = begin; p < end; ++p) {
      Rgb g{};
      for (uint64_t k = links.begin[p]; k < links.begin[p + 1]; ++k) {
        const Rgb& bq = b[links.source[k]];
        for (int band = 0; band < kBands; ++band) g[band] += links.ff[k] * bq[band];
      }
      gathered[p] = g;
    }
  });
  std::vector<Rgb> old(leaves.size());
  for (size_t i = 0; i < leaves.size(); ++i) old[i] = b[leaves[i]];
  ParallelFor(static_cast<int64_t>(tree.roots.size()), 16, c.threads,
              [&](int64_t begin, int64_t end) {
                for (int64_t r = begin; r < end; ++r)
                  PushPull(c, tree, gathered, tree.roots[r], Rgb{}, b);
              });
  Rgb diff{};
  for (size_t i = 0; i < leaves.size(); ++i) {
    const double a = tree.nodes[leaves[i]].area;
    for (int k = 0; k < kBands; ++k) {
      const double d = b[leaves[i]][k] - old[i][k];
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
  c.ray_epsilon = RayEpsilonFor(*roots);
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
  std::vector<Rgb> b(tree.nodes.size());
  for (size_t n = 0; n < tree.nodes.size(); ++n) b[n] = c.MaterialOf(tree.nodes[n]).emission;

  SolveResult& solve = result.solve;
  std::vector<uint32_t> leaves;
  for (int pass = 0; pass < options.max_passes && !solve.cancelled; ++pass) {
    start = std::chrono::steady_clock::now();
    bool changed = false;
    for (int round = 0; round < 64 && RefineRound(c, tree, links, b, stats.rays); ++round) {
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
      const double change = GatherSweep(c, tree, links, leaves, e_norm, b);
      ++solve.iterations;
      solve.residual_history.push_back(change);
      solve.residual = change;
      if (callback) {
        SolveProgress progress;
        progress.iteration = solve.iterations;
        progress.residual = change;
        std::vector<Rgb> snapshot;
        if (solver.snapshot_every > 0 && solve.iterations % solver.snapshot_every == 0) {
          for (uint32_t l : leaves) snapshot.push_back(b[l]);
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
  for (uint32_t l : result.leaves) result.leaf_radiosity.push_back(b[l]);
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
