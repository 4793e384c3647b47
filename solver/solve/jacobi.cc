// Jacobi: each sweep computes the residual r = E + rho F B - B of the current B (one
// SpMV, parallel over rows; streamed when the rows are in a store) and then sets
// B <- B + r = E + rho F B.
#include "solver/solve/methods.h"
#include "solver/solve/stopping.h"

namespace radflux {

absl::Status SolveJacobi(const BandSystem& bands, const SolverOptions& options,
                         const SolveCallback& callback, std::vector<Rgb>& b, SolveResult& result) {
  IterationMonitor monitor(bands, options, callback, result);
  std::vector<Rgb> r;
  while (!monitor.ShouldStop()) {
    const absl::StatusOr<Rgb> relative = LaneResiduals(bands, b, &r);
    if (!relative.ok()) return relative.status();
    const double residual = MaxOverLanes(bands, *relative);
    ParallelFor(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i)
        for (int k = 0; k < bands.lanes; ++k) b[i][k] += r[i][k];
    });
    if (monitor.Record(residual, residual, 0, b)) break;
  }
  return absl::OkStatus();
}

}  // namespace radflux
