// View-factor rows between whole surfaces, one face each (issue 23's per-pair integration):
// each pair is integrated as it needs (surface_pair_integrator.h); only pairs whose shaft may
// hold a blocker (shaft_cull.h) are tested for visibility (shaft_visibility.h), so an
// unobstructed pair costs no segment at all (a far pair's one segment is traced without the
// shaft: its walk costs no more). When the upper triangle of A_i F_ij fits in the
// memory budget (SurfaceRowsBudget) each pair is integrated once, over its smaller
// surface, and reciprocity gives the other factor (exactly reciprocal rows, half the work);
// otherwise rows are computed in parallel, a block at a time, and handed to the sink in
// order: memory is one block of rows, whatever n.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "solver/formfactor/surface_pair_integrator.h"

namespace radflux {

struct SurfaceRowsOptions {
  PairIntegration integration;
  int threads = 0;                   // 0 = all cores
  uint64_t memory_limit = 0;         // bytes for rows in flight, a hard bound; 0 = 64 rows per
                                     // thread (and the triangle within SurfaceRowsBudget(0))
  bool progress = false;             // print rows done and ETA to stderr
  // Called after each block of rows (of the pair triangle's rows when reciprocal) with the
  // rows done and their total; returning false stops the build: CANCELLED.
  std::function<bool(size_t done, size_t total)> on_rows;
};

// The bytes of rows BuildSurfaceRows may hold: `memory_limit` when given (> 0), else
// kDefaultMemoryFraction of the machine's physical memory (kFallbackBudget when the system
// does not say). On a 24 GB machine the default holds the triangle of about 38,000 surfaces.
inline constexpr double kDefaultMemoryFraction = 0.25;
inline constexpr uint64_t kFallbackBudget = uint64_t{512} << 20;
uint64_t SurfaceRowsBudget(uint64_t memory_limit);

// Bytes of the upper triangle of A_i F_ij for n radiating surfaces (n (n - 1) / 2 doubles).
uint64_t TriangleBytes(size_t n);

struct SurfaceRowsStats {
  PairCounts pairs;
  uint64_t blockers = 0;          // surfaces that can block anything (shaft_cull.h filter 1)
  uint64_t traced_pairs = 0;      // pairs that tested segments (one-segment pairs, and
                                  // others whose shaft may hold a blocker)
  uint64_t segments = 0;          // visibility segments tested
  bool reciprocal = false;        // each pair integrated once (the triangle fit the budget)
  uint64_t budget = 0;            // bytes: SurfaceRowsBudget(options.memory_limit)
  uint64_t triangle = 0;          // bytes: TriangleBytes(radiating)
  double cull_seconds = 0, rows_seconds = 0;
  void Merge(const SurfaceRowsStats& o);
};

// Called with rows 0, 1, ..., rows-1 in order; each has one value per radiating surface.
using SurfaceRowSink = std::function<absl::Status(std::span<const double> row)>;

// Rows of F between the first `radiating` shapes; the shapes after them only block (View3D's
// obstruction surfaces). F_ij is the share of what leaves i that j's opaque part intercepts:
// the geometric factor (through partly transparent blockers at their transmission) times
// j's opacity (SurfaceShape::opacity), the rest passing on to what lies behind j; so rows
// of a closed enclosure still sum to 1, and opacity_i A_i F_ij = opacity_j A_j F_ji. Stops
// at the first sink error and returns it.
absl::Status BuildSurfaceRows(const std::vector<SurfaceShape>& shapes, size_t radiating,
                              const SurfaceRowsOptions& options, const SurfaceRowSink& sink,
                              SurfaceRowsStats& stats);

class BlockerBvh;

// BuildSurfaceRows a block of rows at a time, in any order, by anyone (the service's view-
// factor jobs, checkpointed per block): the rows it gives are those of BuildSurfaceRows,
// bit for bit, however they are split into blocks. When reciprocal(), row i of a block is
// the pair triangle's row i (A F to the surfaces after i: RowWidth(i) = n - i - 1 values),
// else row i of F (n values); Emit turns all rows' values into the rows of F.
class SurfaceRowPlan {
 public:
  // The shapes are referenced, not copied: they must outlive the plan. Builds the blockers'
  // hierarchy and decides reciprocal() as BuildSurfaceRows does (stats: blockers, budget,
  // triangle, reciprocal, cull_seconds).
  SurfaceRowPlan(const std::vector<SurfaceShape>& shapes, size_t radiating,
                 const SurfaceRowsOptions& options, SurfaceRowsStats& stats);
  ~SurfaceRowPlan();
  SurfaceRowPlan(const SurfaceRowPlan&) = delete;
  SurfaceRowPlan& operator=(const SurfaceRowPlan&) = delete;

  bool reciprocal() const { return reciprocal_; }
  size_t radiating() const { return radiating_; }
  // Values of row i: n - i - 1 when reciprocal, else n.
  size_t RowWidth(size_t i) const;
  // Values of rows [first, first + count).
  size_t BlockValues(size_t first, size_t count) const;
  // Rows [first, first + count) into `values` (BlockValues of them), on options.threads;
  // adds the pairs' counts to `stats`.
  void BuildBlock(size_t first, size_t count, std::span<double> values,
                  SurfaceRowsStats& stats) const;
  // The rows of F to `sink` in order, given every row's values in row order, one block at a
  // time from `block(first)` (the values of the block starting at row `first`, which holds
  // block_rows rows or the rest): when reciprocal the triangle is assembled first (it fits
  // the budget), else each block's rows go straight to the sink.
  absl::Status Emit(size_t block_rows,
                    const std::function<absl::StatusOr<std::vector<double>>(size_t first)>& block,
                    const SurfaceRowSink& sink) const;

 private:
  const std::vector<SurfaceShape>& shapes_;
  size_t radiating_;
  SurfaceRowsOptions options_;
  std::unique_ptr<BlockerBvh> blockers_;
  bool reciprocal_ = false;
};

}  // namespace radflux
