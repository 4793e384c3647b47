// Gauss-Seidel in row order. A sweep has a parallel phase, upper_i = sum_{j>=i} F_ij B_j
// of the current B, and a serial phase over rows in order that gathers the lower part
// lower_i = sum_{j<i} F_ij B_j from the rows already updated and sets B_i. The lower
// sums kept from the previous sweep make the residual of the current B exact for free.
#include <cmath>

#include "solver/solve/methods.h"
#include "solver/solve/stopping.h"

namespace radflux {
namespace {

// upper_i for every row, and the relative residual of B per lane using `lower`.
Rgb UpperSumsAndResidual(const BandSystem& bands, const std::vector<Rgb>& b,
                         const std::vector<Rgb>& lower, std::vector<Rgb>& upper) {
  const std::vector<double>& area = *bands.area;
  const Rgb norm2 =
      ReduceBlocks(bands.n, kSolveBlock, bands.threads, [&](int64_t begin, int64_t end) {
        Rgb s{};
        for (int64_t i = begin; i < end; ++i) {
          const uint32_t row = static_cast<uint32_t>(i);
          upper[i] = GatherRow(bands, row, b, row, bands.n);
          for (int k = 0; k < bands.lanes; ++k) {
            const double r =
                bands.emission[i][k] + bands.rho[i][k] * (lower[i][k] + upper[i][k]) - b[i][k];
            s[k] += area[i] * r * r;
          }
        }
        return s;
      });
  Rgb relative{};
  for (int k = 0; k < bands.lanes; ++k) relative[k] = std::sqrt(norm2[k]) / bands.emission_norm[k];
  return relative;
}

}  // namespace

absl::Status SolveGaussSeidel(const BandSystem& bands, const SolverOptions& options,
                              const SolveCallback& callback, std::vector<Rgb>& b,
                              SolveResult& result) {
  IterationMonitor monitor(bands, options, callback, result);
  std::vector<Rgb> lower(bands.n), upper(bands.n);
  ParallelFor(bands.n, kSolveBlock, bands.threads, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      lower[i] = GatherRow(bands, static_cast<uint32_t>(i), b, 0, static_cast<uint32_t>(i));
  });
  while (!monitor.ShouldStop()) {
    const double residual = MaxOverLanes(bands, UpperSumsAndResidual(bands, b, lower, upper));
    for (uint32_t i = 0; i < bands.n; ++i) {
      lower[i] = GatherRow(bands, i, b, 0, i);
      for (int k = 0; k < bands.lanes; ++k)
        b[i][k] = bands.emission[i][k] + bands.rho[i][k] * (lower[i][k] + upper[i][k]);
    }
    if (monitor.Record(residual, residual, 0, b)) break;
  }
  return absl::OkStatus();
}

}  // namespace radflux
