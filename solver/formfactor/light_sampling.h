// Emitter columns of a form-factor row by light sampling with a fixed per-row budget:
// each of the row's light samples takes a point x on the receiver patch i (stratified; on one
// patch a few samples share each point, on a group each takes its own), a sampled node s
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
// for every emitter patch j (the emitters that cannot light x have P = 0 and F = 0). Where
// F_s(x), Lambert's exact unoccluded form factor from x, is not small, the direction is
// instead drawn exactly in proportion to cos(theta_x) within s (by rejection from the
// cosine-weighted hemisphere) and the sample adds F_s(x) V / (P(s | x) budget), with the same
// expectation and no spread at all where s is unoccluded (the tiles of a plane then share it
// as the directions fall). So
// the row stays an unbiased form-factor row, whatever the number of emitter patches, at
// `budget` shadow rays. The rays that leave i by the cosine-weighted sampling of the rest of
// the row must drop their emitter hits (monte_carlo does), so that nothing is counted twice.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/formfactor/light_tree.h"
#include "solver/formfactor/row_builder.h"

namespace radflux {

class LightSampler {
 public:
  // The emitter patches of `context`, with their power from context.emission.
  explicit LightSampler(const RowContext& context);

  bool empty() const { return tree_.empty(); }

  // Adds the estimate of F_ij for the emitter patches j (j != i) to `row` from `points`
  // stratified points on i with `per_point` light samples each, seeded from (seed, i);
  // a receiver near an emitter against its size takes up to 16 times the points (about
  // (size / distance)^2). Returns the shadow rays cast (at most 16 * points * per_point,
  // whatever the number of emitter patches).
  uint64_t AddEmitterColumns(uint32_t i, int points, int per_point, uint64_t seed,
                             RowAccumulator& row) const;

  // Adds the estimate of F_cj, cell c's (context.cells) area-averaged form factor to each
  // emitter unknown j, to `row`: cell c of a group of k cells takes ceil(budget / k) light
  // samples (times its own near-field factor), each at its own stratified point over the
  // cell's patches by area, seeded from (seed, c) apart from the rows' patterns. So the
  // cells of a group share one row's budget of light samples, spread over the group's cells
  // (cell_direct.h). Returns the shadow rays cast.
  uint64_t AddCellEmitterColumns(uint32_t c, int budget, uint64_t seed, RowAccumulator& row) const;

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
  // choices are stratified over [0, 1) across the directions.size() samples.
  void SamplePoint(const Vec3& x, const Vec3& n, uint32_t receiver, uint64_t seed, uint64_t index,
                   uint32_t first, std::span<const Point2> directions, std::vector<StreamRay>& rays,
                   std::vector<PendingSample>& pending) const;

 private:
  // The light samples of `points` stratified points of `sample_point`, `per_point` each, for
  // `receiver` (never its own emitter), patterns seeded from (seed, index).
  uint64_t AddSamples(const UnknownPointSampler& sample_point, uint32_t receiver, int points,
                      int per_point, uint64_t seed, uint64_t index, RowAccumulator& row) const;

  const RowContext& context_;
  LightTree tree_;
};

}  // namespace radflux
