// Hierarchical radiosity (Hanrahan, Salzman and Aupperle 1991) with clustering (Smits, Arvo
// and Greenberg 1994): every input face is the root of a quadtree (quads) or 4-way triangle
// subdivision, and a binary cluster hierarchy (ClusterTree) stands above the faces; light
// moves along links between nodes (clusters or elements) at whatever level the link's error
// estimate allows, and B is solved by gathering over the links with push-pull.
//
// Links start from the top cluster's link with itself (one link; without clusters, one per
// ordered pair of faces, O(faces^2)). A cluster's link with itself is always replaced by the
// links among its children (so no link joins a cluster to its own descendant); any other link
// p <- q (p gathers from q) is refined when its error in power
//   rho_p A_p (B_q * spread_pq + F_pq * range_q) > link_epsilon * (total emitted power)
// where spread_pq is how much F(x, q) varies over p (the whole unoccluded F when a shadow edge
// may cross p; for a link with a cluster end, the bound ClusterFormFactorBound) and range_q
// how much B varies over q's leaves (rho_p A_p of a cluster: the sum over its faces). Between
// elements the receiver is split when the first term dominates, else the source, down to
// min_area_fraction of the total area; a link with a cluster end splits the larger of two
// clusters (by bounding sphere), or the cluster when the other end is an element (clusters
// always split, so such links end on faces when they must), and is
// refined whatever its error while its bound is above 0.3 (its estimate sees the faces from
// afar, which needs a small solid angle; before the first solve most B are still zero).
// Links between elements use EstimateElementLink, links with a cluster end
// EstimateClusterLink. A cluster sends the exposed-area mean B of its faces; what a cluster
// gathers goes to each of its faces by that face's own orientation toward the source
// (PointTransfer at the face's centroid; a face turned away gets nothing), then down the face's
// element tree by push-pull.
// Radiosity is kept per exposed area (ExposedFraction): what is buried inside a solid neither
// receives nor sends light, and outputs show the area mean (zero where buried).
// Partly transparent faces (Material::opacity < 1) as in the uniform solver: shadow rays pass
// through them as the caster decides, and a node sends, reflects and emits from its opaque
// part only (link form factors to it, rho A and emitted power are times its opacity; B is the
// opaque part's radiosity).
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/hierarchical/cluster_tree.h"
#include "solver/mesh/adaptive_tree.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"
#include "solver/solve/solver.h"

namespace radflux {

struct HierarchicalOptions {
  bool enabled = false;             // `radflux solve --solver hierarchical`
  double link_epsilon = 1e-4;       // BFA threshold, relative to the total emitted power
  double min_area_fraction = 2e-5;  // no element smaller than this fraction of total area
                                    // (`--min-element-area`)
  int samples = 4;                  // points per receiver element (one shadow ray each)
  int max_passes = 6;               // refine-then-solve passes (stops early when stable)
  bool clusters = true;             // cluster hierarchy above the faces (`--clusters on|off`)
  uint64_t seed = 1;                // sample patterns are seeded per element from it
};

// Sparse link set, CSR by receiver slot: the links gathered by slot s are [begin[s],
// begin[s+1]); slots [0, elements) are the elements, slot elements + c is cluster c.
struct LinkSet {
  uint32_t elements = 0;
  std::vector<uint64_t> begin{0};
  std::vector<uint32_t> source;  // node gathered from: an element, or kClusterBit | cluster
  std::vector<float> ff;         // F_pq with visibility; for a cluster receiver, the
                                 // EstimateClusterLink k (scene units^2) the gather uses
  std::vector<float> spread;     // max - min of F(x, q) over x in p (LinkEstimate::spread)

  size_t size() const { return source.size(); }
  size_t Slots() const { return begin.size() - 1; }
  // The node id gathering at slot s.
  uint32_t Receiver(size_t s) const {
    return s < elements ? static_cast<uint32_t>(s)
                        : kClusterBit | static_cast<uint32_t>(s - elements);
  }
  size_t Bytes() const {
    return begin.size() * sizeof(uint64_t) + source.size() * (sizeof(uint32_t) + 2 * sizeof(float));
  }
};

struct HierarchicalStats {
  size_t roots = 0, elements = 0, leaves = 0;
  size_t clusters = 0;       // clusters above the faces (0 with clusters off)
  size_t initial_links = 0;  // links before the first refinement
  size_t links = 0;          // final link count
  size_t link_bytes = 0;     // bytes of the final LinkSet
  size_t element_bytes = 0;  // bytes of the element tree
  size_t patches = 0;        // patches of the conforming output mesh
  int passes = 0, refine_rounds = 0;
  uint64_t rays = 0;
  double refine_seconds = 0, solve_seconds = 0;
};

struct HierarchicalResult {
  ElementTree tree;
  LinkSet links;
  std::vector<uint32_t> leaves;      // leaf elements in output order
  std::vector<Rgb> leaf_radiosity;   // B per leaf, W/m^2 per band
  PatchMesh mesh;                    // conforming mesh of the leaves (BuildLeafMesh)
  std::vector<uint32_t> patch_leaf;  // mesh patch -> index into leaves
  SolveResult solve;                 // radiosity per mesh patch (its leaf's B)
  HierarchicalStats stats;
};

// Solves a validated scene. `solver` supplies tolerance (on the opaque-area-weighted relative
// change of B per gathering sweep), max_iterations, threads, snapshot_every and cancel. The callback
// gets every sweep; snapshots hold one entry per current leaf in depth-first order (the leaf
// set grows between refinement passes; the final one maps to mesh patches by patch_leaf).
absl::StatusOr<HierarchicalResult> SolveHierarchical(const Scene& scene,
                                                     const HierarchicalOptions& options,
                                                     const SolverOptions& solver,
                                                     const SolveCallback& callback = {});

}  // namespace radflux
