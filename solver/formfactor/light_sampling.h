// Emitter columns of a form-factor row by light sampling with a fixed per-row budget:
// each of the row's light samples takes a point x on the receiver patch i (stratified; on one
// patch, or a direct-light cell of one patch, a few samples share each point, on a group each
// takes its own; on a group or a cell their choices of s are stratified across them), a
// sampled node s
// chosen with probability P(s | x) (LightTree: one emitter, or a plane of emitters that tile
// a rectangle; by the tree's cut at x: near x, or among at most 16 emitters, in proportion
// to their exact unoccluded contributions), a direction in the solid angle Omega_s that s
// subtends at x with pdf (EmitterPointSampler: by area for far shapes, by solid angle for
// near ones, both warped towards the integrand), and one shadow ray to the point y it meets;
// the sample is credited to the emitter patch j that holds y (s itself, or the tile of a
// tiled plane; LightTree::Locate). It adds
//     cos(theta_x) V / (pi pdf P(s | x) budget)
// to F_ij. Its expectation over x, s and the direction is
//     (1 / A_i) integral_{A_i} (1 / pi) integral_{Omega_j} cos(theta_x) V dw dA = F_ij
// for every emitter patch j (the emitters that cannot light x have P = 0 and F = 0).
//
// Where F_s(x), Lambert's exact unoccluded form factor from x, is at least
// kRejectionFormFactor (an emitter near x or filling much of its hemisphere: a lamp's
// cavity, the bars of a frame around each other), the direction is instead drawn exactly in
// proportion to cos(theta_x) within s (by rejection from the cosine-weighted hemisphere):
// the density of the row's own cosine rays restricted to s. There the row's k cosine rays
// that meet an emitter are not dropped: the two are combined by multiple importance
// sampling with the balance heuristic. With N light samples, a sample's density on
// (x, direction) is P(s | x) cos / (pi F_s(x) A_i) and a cosine ray's cos / (pi A_i), so each
// unoccluded light sample and each cosine ray that meets s's front adds
//     F_s(x) / (k F_s(x) + N P(s | x))
// to F_ij (j the patch met): the same value, whatever the direction. Below
// kRejectionFormFactor only the light samples count (the cosine rays' weight is 0 there, on
// both sides of the rule, which is a function of (x, s) alone). Either way the row stays an
// unbiased form-factor row, whatever the number of emitter patches, at `budget` shadow rays;
// and where emitters fill the hemisphere, the cosine rays' hits on them and on the rest of
// the row are drawn together, so the row's sum is less noisy than either part (its
// non-emitter entries and emitter entries no longer vary independently).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "solver/formfactor/cell_columns.h"
#include "solver/formfactor/light_tree.h"
#include "solver/formfactor/row_builder.h"

namespace radflux {

// The light samples a group's direct-light cells take together (cell_direct.h), which are
// also the group row's emitter columns (monte_carlo): 4 times a row's, stratified over the
// cells. On a plate's 28 groups of 16 cells under a small lamp (face_grouping_test) the
// groups' direct light is 0.35% RMS off its closed form, against 1.0% with a row's budget
// over the cells and 1.4-2.2% with the row's own samples. The conference room's rays: 0.73 M
// (the push-down reads the rows' samples: cell_columns.h) against 0.57 M with a row's budget.
inline int CellLightSamplesPerGroup(const FormFactorOptions& o) {
  return 4 * LightSamplesPerRow(o);
}

// How many of a cell's `samples` light samples share one point (and its cut of the light
// tree, most of a sample's cost among many emitters: half the classroom's instructions when
// each of its cells' samples cut at a point of its own): a cell of one patch, as a single patch's
// row, up to kLightSamplesAtAPoint (the point rounds the cell's samples up to a multiple of it); a
// cell of several patches, whose direct light varies across its members as a group's does, one (a
// plate's cells of ~7 triangles under a small lamp: 0.32-0.39% RMS off the closed form over its
// groups, 0.9-1.3% at 4 a point; face_grouping_test).
inline int CellSamplesAtAPoint(int samples, size_t patches) {
  return patches == 1 ? std::clamp(samples, 1, kLightSamplesAtAPoint) : 1;
}

// The shapes of `context`'s emitting unknowns (each one patch), in unknown order, their power
// from context.emission: the LightTree of a LightSampler.
std::vector<EmitterShape> EmitterShapes(const RowContext& context);

class LightSampler {
 public:
  // The emitter patches of `context`, with their power from context.emission. With
  // `near_field`, a receiver's near-field factor (AddEmitterColumns: more points near an
  // emitter) is measured to near_field's emitters instead of this sampler's (bright
  // reflectors, bright_reflectors.h, sampled beside the emitters, add no points: their
  // columns came from the cosine rays alone before).
  explicit LightSampler(const RowContext& context, const LightSampler* near_field = nullptr);

  bool empty() const { return tree_.empty(); }

  // A cosine ray of row i that met the front of emitter unknown `emitter`, from receiver
  // point x (on i, before any lift off it) with unit normal n.
  struct CosineHit {
    Vec3 x, n;
    uint32_t emitter = 0;
  };
  // Adds the estimate of F_ij for the emitter patches j (j != i) to `row` from `points`
  // stratified points on i with `per_point` light samples each, seeded from (seed, i),
  // combined with the `hits` of the row's `cosine_rays` cosine rays on emitters (above);
  // a receiver near an emitter against its size takes up to 16 times the points (about
  // (size / distance)^2), scaled by `area_share`, the row's area against the mean row's
  // (RowNearFieldFactor; 1: all of them). Returns the shadow rays cast (at most 16 * points *
  // per_point, whatever the number of emitter patches).
  uint64_t AddEmitterColumns(uint32_t i, int points, int per_point, uint64_t seed,
                             RowAccumulator& row, std::span<const CosineHit> hits = {},
                             uint32_t cosine_rays = 0, double area_share = 1) const;

  // Cell c's (context.cells) area-averaged form factor F_cj to each emitter unknown j, into
  // `columns` (emptied first): cell c of a group of k cells takes ceil(budget / k) light
  // samples (times its own near-field factor) at stratified points over the cell's patches by
  // area, CellSamplesAtAPoint of them a point, their choices of emitter stratified across
  // the cell's samples, seeded from (seed, c) apart from the rows' patterns. So the cells of
  // a group share a budget of light samples spread over the group (cell_direct.h). Returns
  // the shadow rays cast.
  uint64_t CellEmitterColumns(uint32_t c, int budget, uint64_t seed,
                              std::vector<CellColumn>& columns) const;
  // Adds group g's emitter columns as its cells estimate them: sum over the cells c of g of
  // (A_c / A_g) F_cj, each F_cj by CellEmitterColumns(c, budget, seed), the very samples
  // cell_direct.h takes after the solve; keeps each cell's F_cj in context.cell_columns when
  // it is set. Returns the shadow rays cast.
  uint64_t AddGroupEmitterColumns(uint32_t g, int budget, uint64_t seed, RowAccumulator& row) const;

  // One light sample waiting for its shadow ray: the emitter patch it chose and its
  // estimate of that emitter's form factor F_j(x) from the receiver point, if the ray is
  // unoccluded (divide by the samples drawn at the point: their mean estimates F_j(x)).
  struct PendingSample {
    uint32_t emitter = 0;
    double form_factor = 0;
  };
  // The light samples number first + k, k < directions.size(), at receiver point x (unit
  // normal n) on patch `receiver` (never sampled as its own emitter), seeded from (seed,
  // index), with one multi-jittered direction sample each: appends the shadow rays of those
  // that can see an emitter to `rays` and their samples to `pending`, index for index. The
  // choices are stratified over [0, 1) across the directions.size() samples. `cosine_share`
  // is k / N of a row that combines N light samples with k cosine rays (0: light samples
  // alone). With `strata` > 0 (the samples of a set of `strata`, this point's numbered from
  // `first`), the choices are stratified across the set instead.
  void SamplePoint(const Vec3& x, const Vec3& n, uint32_t receiver, uint64_t seed, uint64_t index,
                   uint32_t first, std::span<const Point2> directions, std::vector<StreamRay>& rays,
                   std::vector<PendingSample>& pending, double cosine_share = 0,
                   uint32_t strata = 0) const;

 private:
  // The light samples of `points` stratified points of `sample_point`, `per_point` each, for
  // `receiver` (never its own emitter), patterns seeded from (seed, index). Each unoccluded
  // sample adds its estimate to its emitter's column by add(j, v). Their choices of emitter
  // are stratified across all of them when per_point is 1 or `choices_across_set`, else
  // across each point's.
  template <typename AddFn>
  uint64_t AddSamples(const UnknownPointSampler& sample_point, uint32_t receiver, int points,
                      int per_point, uint64_t seed, uint64_t index, double cosine_share,
                      const AddFn& add, bool choices_across_set = false) const;
  // A cosine ray's share of F_ij for its hit (above): F_s(x) / (k F_s(x) + N P(s | x)) where
  // F_s(x) >= kRejectionFormFactor, else 0.
  double CosineHitValue(const CosineHit& hit, double k, double n) const;

  const RowContext& context_;
  LightTree tree_;
  const LightTree& near_field_;       // the tree whose emitters set the near-field factor
  std::vector<uint32_t> tree_index_;  // per unknown: its index among the tree's emitters
};

}  // namespace radflux
