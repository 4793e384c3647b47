// BandSystem: the per-band view of a RadiositySystem that every method solves. The
// bands that need solving are packed into "lanes" (lane k solves band `band[k]`): one
// lane for a grey scene, otherwise one per band that emits somewhere. Per-patch lane
// values are stored as Rgb with lanes >= `lanes` unused. All reductions here are
// summed per fixed block and then in block order, so results never depend on threads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/core/parallel.h"
#include "solver/solve/solver.h"
#include "solver/sparse/csr_matrix.h"
#include "solver/sparse/row_store.h"

namespace radflux {

// Rows per ParallelFor block for loops that gather rows (SpMV); fixed so that results
// do not depend on threads.
inline constexpr int64_t kSolveBlock = 256;
// Entries per block for O(n) vector loops and their reductions: large, so that small
// systems run them without the cost of a parallel region.
inline constexpr int64_t kVectorBlock = 8192;

struct BandSystem {
  const CsrMatrix* f = nullptr;     // the rows in memory, or null when they stream from
  const RowStore* store = nullptr;  // a row store (jacobi and gauss_seidel only)
  uint32_t n = 0;
  int lanes = 0;                              // bands actually solved (0: nothing emits)
  bool grey = false;                          // lane 0 stands for all three bands
  std::array<int, kBands> band{};             // band solved in lane k
  const std::vector<double>* area = nullptr;  // per patch, scene units^2
  std::vector<Rgb> rho;                       // reflectance per patch per lane
  std::vector<Rgb> emission;                  // E per patch per lane, W/m^2
  Rgb emission_norm{};                        // ||E||_A per lane (> 0 for every lane)
  double total_area = 0;
  int threads = 0;  // for ParallelFor (0 = all cores)
};

// The lanes of `system` (grey: one; else the bands with any emission). Inputs must be valid.
BandSystem MakeBandSystem(const RadiositySystem& system, int threads);

// Per-patch Rgb (all bands) -> lane values.
std::vector<Rgb> PackLanes(const BandSystem& bands, const std::vector<Rgb>& rgb);
// Lane values -> all bands: a grey lane is copied to every band, unsolved bands are 0.
void UnpackLanes(const BandSystem& bands, const std::vector<Rgb>& lanes, std::vector<Rgb>& rgb);

// Deterministic parallel sum of per-block Rgb partials: partial(begin, end) per fixed
// block of `block` indices, added in block order.
template <typename Partial>
Rgb ReduceBlocks(int64_t count, int64_t block, int threads, Partial&& partial) {
  const int64_t blocks = (count + block - 1) / block;
  std::vector<Rgb> sums(static_cast<size_t>(blocks), Rgb{});
  ParallelFor(count, block, threads, [&](int64_t begin, int64_t end) {
    sums[static_cast<size_t>(begin / block)] = partial(begin, end);
  });
  Rgb total{};
  for (const Rgb& s : sums)
    for (int k = 0; k < kBands; ++k) total[k] += s[k];
  return total;
}

// sum_i A_i x_ik y_ik per lane.
Rgb AreaDot(const BandSystem& bands, const std::vector<Rgb>& x, const std::vector<Rgb>& y);

// Calls fn on consecutive ranges of rows in order: the whole matrix at once, or each chunk
// of the row store as it streams in. Returns the store's read error.
absl::Status ForEachRowRange(const BandSystem& bands, const RowsFn& fn);

// Sum over the entries of row i (in `rows`) with column in [col_begin, col_end) of
// F_ij x_j, per lane.
Rgb GatherRow(const BandSystem& bands, const RowsView& rows, uint32_t i, const std::vector<Rgb>& x,
              uint32_t col_begin, uint32_t col_end);

// The stopping measure per lane: ||r||_A / ||R||_A, the residual against the reflected part
// R = rho F B of the same B (at the solution R = B - E), so a small bright emitter cannot
// make a loose solve look tight. Where R is 0 (B = 0, or no light reflects) ||E||_A stands
// in for it. Summed per fixed block of kSolveBlock rows in block order (the same numbers as
// a ReduceBlocks over r), on the calling thread.
Rgb ResidualMeasures(const BandSystem& bands, const std::vector<Rgb>& r,
                     const std::vector<Rgb>& reflected);

// r = E + rho F B - B (if `r` is non-null, stored there) and ResidualMeasures per lane;
// one pass over the rows (streamed when they are in a store: its read error).
absl::StatusOr<Rgb> LaneResiduals(const BandSystem& bands, const std::vector<Rgb>& b,
                                  std::vector<Rgb>* r);

// LaneResiduals for methods that need every row in memory (bands.f set): cannot fail.
Rgb ResidentLaneResiduals(const BandSystem& bands, const std::vector<Rgb>& b, std::vector<Rgb>* r);

// Largest rho_i * sum_j F_ij over rows and lanes: q < 1 bounds the max-norm error of B by
// ||r||_inf / (1 - q) (the rows as a contraction); a pass over the rows.
absl::StatusOr<double> MaxReflectedRowSum(const BandSystem& bands);

// Per lane max_i |x_i|.
Rgb MaxNorms(const BandSystem& bands, const std::vector<Rgb>& x);

// The larger of the first `bands.lanes` components.
double MaxOverLanes(const BandSystem& bands, const Rgb& v);

}  // namespace radflux
