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
#include <span>
#include <vector>

#include "absl/status/status.h"
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

}  // namespace radflux
