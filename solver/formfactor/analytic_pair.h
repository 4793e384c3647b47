// The analytic estimate of one form factor F_ij: Lambert's exact point-to-polygon
// form factor at stratified points on patch i, times visibility by shadow rays.
// Used by the analytic builder for every column and by monte_carlo and hemicube for
// emitters.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/formfactor/contour_cache.h"
#include "solver/formfactor/pair_patches.h"
#include "solver/formfactor/row_builder.h"

namespace radflux {

// s stratified points on patch i, seeded from (seed, i).
std::vector<Vec3> PatchSamplePoints(const PatchMesh& mesh, uint32_t i, int s, uint64_t seed);

// The patches flagged as emitters in `context`, ascending.
std::vector<uint32_t> EmitterPatches(const RowContext& context);

// The analytic pairs of one RowContext's mesh, with the per-patch data they read laid out
// once (PairPatches). Every estimate depends only on (mesh, i, points, j, seed).
class AnalyticPairs {
 public:
  explicit AnalyticPairs(const RowContext& context);

  // False when i and j cannot exchange light: j wholly behind i's plane or i wholly
  // behind j's (back-facing and behind-the-plane pairs are never traced).
  bool CanExchange(uint32_t i, uint32_t j) const;

  // F_ij from `points` on i: the mean exact unoccluded point-to-polygon form factor,
  // times the visible fraction of the pairs (x_m, y_m) (y_m stratified on j) weighted by
  // the form-factor kernel cos cos / r^2. Weighting by the kernel makes the estimate
  // consistent when visibility varies across j (an unweighted 0/1 average is biased where
  // the near part of j is hidden and the far part is not). Adds the shadow rays to `rays`.
  double FormFactor(uint32_t i, const std::vector<Vec3>& points, uint32_t j, uint64_t seed,
                    uint64_t& rays) const;

  // Adds F_ij of row i for every j in `columns` that can exchange light with i, from
  // s = `samples` points on i; returns the shadow rays cast.
  uint64_t AddColumns(uint32_t i, std::span<const uint32_t> columns, int samples, uint64_t seed,
                      RowAccumulator& row) const;
  // The same from given points on i (e.g. s copies of the centroid: s shadow rays from it),
  // with the contour integrals shared through `contours` when given (begun on row i and
  // `points`): the same values, about half the work when the columns are most patches.
  uint64_t AddColumns(uint32_t i, std::span<const uint32_t> columns,
                      const std::vector<Vec3>& points, uint64_t seed, RowAccumulator& row,
                      ContourCache* contours = nullptr) const;

  // The per-patch data the pairs read (for a ContourCache of the same mesh).
  const PairPatches& Patches() const { return patches_; }

 private:
  const RowContext& context_;
  PairPatches patches_;
};

}  // namespace radflux
