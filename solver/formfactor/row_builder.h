// RowBuilder: computes the sparse form-factor row F_i. of one patch. The three
// methods (monte_carlo, hemicube, analytic) implement it; BuildRowBlock and
// BuildFormFactors run any of them over blocks of consecutive patches.
// A row depends only on (mesh, options, seed, i): never on the thread or block.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/cancel.h"
#include "solver/core/sampling.h"
#include "solver/formfactor/form_factor_options.h"
#include "solver/formfactor/row_accumulator.h"
#include "solver/mesh/patch_clusters.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/raytrace/ray_caster.h"
#include "solver/sparse/csr_matrix.h"
#include "solver/sparse/row_store.h"

namespace radflux {

class CellColumnCache;
class ReciprocalPairs;

// What the row builders need to know about the scene besides its geometry. Rows and
// columns are unknowns: the mesh's patches, or the groups of them in `clusters` (rays still
// hit patches: UnknownOf maps them). Only monte_carlo builds rows of grouped unknowns.
// The most light a row may return through its patch's reflectance, rho * (row sum): sampled
// rows above it are scaled back to it (MaxRowSum).
inline constexpr double kMaxRowGain = 0.999;

struct RowContext {
  const PatchMesh* mesh = nullptr;
  const RayCaster* caster = nullptr;
  const PatchClusters* clusters = nullptr;  // null: unknown u is patch u
  // Grouped: the direct-light cells (face_grouping.h), each inside one unknown, which get
  // their own direct light after the solve (cell_direct.h).
  const PatchClusters* cells = nullptr;
  std::vector<uint32_t> cell_first, cell_order;  // cells of unknown u, in cell order:
                                                 // cell_order[cell_first[u], cell_first[u + 1])
  // Where the group rows keep their cells' emitter columns for the push-down (cell_columns.h;
  // null: not kept, the push-down draws them again).
  CellColumnCache* cell_columns = nullptr;
  std::vector<uint8_t> needs_row;  // per unknown, 1 where rho > 0 in some band: only those get rows
  std::vector<uint8_t> emitter;    // 1 where the unknown emits
  std::vector<double> emission;    // E summed over bands, W/m^2 (light sampling's importance;
                                   // empty: every emitter counts as 1)
  std::vector<double> reflectance;  // rho, max over bands, per unknown (empty: 1 for all)
  std::vector<double> opaque_area;  // PatchAttributes::area per unknown, scene units^2
  double mean_row_area = 0;         // MeanRowArea over the unknowns with rows (row_rays.h)
  // Per unknown, the share of its area not enclosed in a solid (exposed_area.h; empty: all 1):
  // monte_carlo scales its row by 1 / exposure, the solve weighs it by its exposed area.
  std::vector<float> exposure;
  double ray_epsilon = 0;  // ray origin offset along the normal, scene units

  // The number of unknowns: rows and columns.
  uint32_t Unknowns() const {
    return static_cast<uint32_t>(clusters ? clusters->size() : mesh->size());
  }
  // The unknown that patch p belongs to.
  uint32_t UnknownOf(uint32_t p) const { return clusters ? clusters->of_patch[p] : p; }
  // Whether unknown u is a single patch, and its (first) patch.
  bool SinglePatch(uint32_t u) const {
    return clusters == nullptr || clusters->first[u + 1] - clusters->first[u] == 1;
  }
  uint32_t FirstPatch(uint32_t u) const { return clusters ? clusters->Members(u)[0] : u; }
  // The largest row sum unknown u's row may keep so that rho_u * sum <= kMaxRowGain (the
  // iterations then converge for every rho < 1): 1 where rho >= kMaxRowGain, more below.
  double MaxRowSum(uint32_t u) const;
  // The direct-light cells of unknown u (empty without cells).
  std::span<const uint32_t> CellsOf(uint32_t u) const {
    if (cells == nullptr) return {};
    return {cell_order.data() + cell_first[u], cell_order.data() + cell_first[u + 1]};
  }
  // Whether unknown u emits (false for one the context does not flag).
  bool Emits(uint32_t u) const { return u < emitter.size() && emitter[u] != 0; }
  // The cosine rays of unknown u's Monte Carlo row at k rays a row on average (row_rays.h:
  // by its opaque area, or the emitters' count): every reader of a row's rays asks here.
  uint32_t RowRays(uint32_t u, int k) const;
  double Exposure(uint32_t u) const { return u < exposure.size() ? exposure[u] : 1.0; }
  // Unknown u's opaque area (0 for one the context does not size).
  double OpaqueArea(uint32_t u) const { return u < opaque_area.size() ? opaque_area[u] : 0; }
  // The cosine-weighted ray about `at`'s normal for u in [0, 1)^2 (SampleCosineHemisphere),
  // from `at` lifted off its surface by ray_epsilon: a row's ray from one of its points.
  StreamRay CosineRay(const SurfacePoint& at, Point2 u) const {
    StreamRay ray;
    ray.SetOrigin(at.x + at.n * ray_epsilon);
    ray.SetDirection(Frame::FromNormal(at.n).ToWorld(SampleCosineHemisphere(u)));
    return ray;
  }
  // Unknown u's area, scene units^2.
  double Area(uint32_t u) const { return clusters ? clusters->area[u] : mesh->patches[u].area; }
};

class RowBuilder {
 public:
  virtual ~RowBuilder() = default;
  // Adds F_ij (j != i) for patch i into `row`; returns the number of rays cast.
  virtual uint64_t BuildRow(uint32_t i, RowAccumulator& row) const = 0;
  // The pass all rows take once built, wherever they are (FinishRows): monte_carlo's
  // reciprocity averaging (reciprocal_pairs.h); null for the others, whose rows stay as built.
  virtual const ReciprocalPairs* Pairs() const { return nullptr; }
};

std::unique_ptr<RowBuilder> MakeRowBuilder(const RowContext& context,
                                           const FormFactorOptions& options);

struct RowBlockStats {
  uint64_t rays = 0;
  double dropped_sum = 0;      // sum over rows of the F_ij dropped by the cut-off (never
                               // an emitter column's: those are kept whatever their size)
  double max_row_dropped = 0;  // the largest such sum in one row
  double dropped_area = 0;     // sum over rows of A_i times the row's dropped sum, scene
                               // units^2: times a radiosity, the power the cut-off dropped
  // The rows the row-sum cap scaled back (RowContext::MaxRowSum), in row order.
  std::vector<ScaledRow> scaled_off;
  // Adds o's sums and appends its scaled rows (blocks merged in row order keep them so).
  void Merge(const RowBlockStats& o);
};

// Rows [first, first + count) as one block; `row` is scratch of size n. Entries below
// `cutoff` are dropped except in emitter columns (context.emitter).
RowBlock BuildRowBlock(const RowBuilder& builder, const RowContext& context, double cutoff,
                       uint32_t first, uint32_t count, RowAccumulator& row, RowBlockStats& stats);

struct FormFactorResult {
  CsrMatrix matrix;
  RowBlockStats stats;
  double seconds = 0;
};

// Rows built by `builder`, all in memory, after its pass (RowBuilder::Pairs), on `threads`.
void FinishRows(const RowBuilder& builder, int threads, CsrMatrix& rows);
// Rows built by `builder` into the finished store `rows`, after its pass: `rows` itself when
// the builder has none, else a new store of the averaged rows spilling to a FileBlockSpill in
// `spill_directory` ("" = a fresh one under $TMPDIR). The new store keeps in memory what
// `rows` leaves of its budget (the rows in memory never pass it); the averaging works in
// ranges of two of its chunks, its back hits in a bucket file in the same directory, its IO
// bounded (reciprocal_pairs.h). The same rows as FinishRows in memory, bit for bit. Returns a
// store's or the bucket file's error (disk full, IO).
absl::StatusOr<std::unique_ptr<RowStore>> FinishRows(const RowBuilder& builder, int threads,
                                                     std::unique_ptr<RowStore> rows,
                                                     const std::string& spill_directory);

// All rows of the mesh, in parallel over blocks, then the builder's pass over them
// (FinishRows). Returns CANCELLED when progress returns false.
absl::StatusOr<FormFactorResult> BuildFormFactors(const RowContext& context,
                                                  const FormFactorOptions& options,
                                                  const PhaseProgress& progress = {});

struct RowBuildSummary {
  std::unique_ptr<RowStore> store;  // the rows
  RowBlockStats stats;
  double seconds = 0;
};

// All rows of the mesh, in parallel over blocks, appended to `store` in row order as they
// finish (rows that do not fit its budget spill while the build goes on), then the builder's
// pass (FinishRows, spilling to `spill_directory`): the same rows as BuildFormFactors. Returns
// CANCELLED when progress returns false, or a store's error.
absl::StatusOr<RowBuildSummary> BuildFormFactorsInto(const RowContext& context,
                                                     const FormFactorOptions& options,
                                                     std::unique_ptr<RowStore> store,
                                                     const std::string& spill_directory,
                                                     const PhaseProgress& progress = {});

// How far a ray's origin is lifted off its surface along the normal, in units of the scene's
// single-precision spacing (float epsilon times its largest coordinate magnitude).
inline constexpr double kRayLiftUlps = 4;

// The ray offset of `mesh`: kRayLiftUlps float spacings at its largest coordinate, the least
// that keeps a single-precision ray off its own face (rays are traced in float, their origins
// rounded to it; a twentieth of a spacing let 36% of a turned cube's rays meet their own faces'
// backs, ray_lift_test.cc). The scene-relative offset before (1e-5 of the diagonal) lifted
// origins past nearby faces, so rays from where surfaces touch or nearly touch passed through
// them and were lost: the conference room's lamps' rows lost 12.1% of their light, 11.3% at
// this lift (bench/escaped_by_material).
double RayEpsilonFor(const PatchMesh& mesh);

}  // namespace radflux
