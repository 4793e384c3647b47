// Adaptive meshing: solve on a coarse uniform mesh, then split the patches whose reflected
// radiosity (B - E) differs from a same-face neighbour's by more than `threshold` times the
// scene's area-mean reflected radiosity, across which an emitter's visibility changes (of
// the shadow rays from the patch to an emitting face some are blocked and some not), or
// which straddle a contact line (of its probe rays some start buried under a solid: their
// first hit is a back face); emitters themselves are not split. Recompute only the rows of new
// patches and the rows that point at split ones, and re-solve warm-started from the previous
// answer. Rows come from the job's method: analytic rows are patched entry by entry (sample points
// fixed per element, so an unchanged row keeps its points); monte_carlo / hemicube rows, whose rays
// name the patch they hit, are rebuilt whole on the new leaves.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/formfactor/form_factor_options.h"
#include "solver/mesh/adaptive_tree.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/ray_caster.h"
#include "solver/scene/scene.h"
#include "solver/solve/solver.h"
#include "solver/sparse/csr_matrix.h"

namespace radflux {

struct AdaptiveOptions {
  int passes = 0;                // refinement passes after the first solve (0: adaptive off)
  double threshold = 0.1;        // split where |B_i - B_j| > threshold * mean B; 0 splits all
  int64_t max_patches = 200000;  // patch budget
  int max_depth = 6;             // splits below one initial patch
  int visibility_rays = 8;       // shadow rays per patch per emitting face, and contact probes
};

struct AdaptivePass {
  size_t patches = 0;          // leaves after this pass's splits
  size_t split = 0;            // patches split
  size_t rows_recomputed = 0;  // rows built in full (new patches) or patched (pointing at them)
  size_t entries_computed = 0;
  double seconds = 0;      // rows + solve of this pass
  double change_in_b = 0;  // area-weighted RMS of B(new) - B(previous), relative to RMS B
};

struct AdaptiveResult {
  ElementTree tree;
  std::vector<uint32_t> leaves;
  PatchMesh leaf_mesh;     // one patch per leaf (the solved unknowns)
  CsrMatrix form_factors;  // rows of leaf_mesh
  std::vector<Rgb> leaf_radiosity;
  PatchMesh mesh;  // conforming display mesh (BuildLeafMesh)
  std::vector<uint32_t> patch_leaf;
  SolveResult solve;                 // of the last pass, radiosity per leaf
  std::vector<AdaptivePass> passes;  // passes[0] is the initial uniform solve
  uint64_t rays = 0;
};

// Whether some of `rays` cosine rays from stratified points on `e` (pattern seeds them)
// start buried (the first thing they hit is a back face: under a block, a pillar, a lamp
// hung below the ceiling) and some do not: the element straddles a contact line, where its
// mean B mixes lit and unlit area (the dark rim, or leak, of a mesh that does not follow
// it). `epsilon` lifts ray origins off the element; `cast` counts the rays.
bool StraddlesContact(const Element& e, const RayCaster& caster, int rays, uint32_t pattern,
                      double epsilon, uint64_t& cast);

// `mesh` gives the initial uniform mesh; form_factors gives the rows' method and knobs.
absl::StatusOr<AdaptiveResult> SolveAdaptive(const Scene& scene, const MeshOptions& mesh,
                                             const FormFactorOptions& form_factors,
                                             const SolverOptions& solver,
                                             const AdaptiveOptions& options,
                                             const SolveCallback& callback = {});

}  // namespace radflux
