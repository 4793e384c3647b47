// Gauss-Seidel in row order. A sweep goes over ranges of consecutive rows in order (the
// whole matrix at once, or each chunk of a row store as it streams in); per range it has a
// parallel phase, upper_i = sum_{j>=i} F_ij B_j (no B_j with j >= i has changed yet in
// this sweep), and a serial phase over the range's rows that gathers the lower part
// lower_i = sum_{j<i} F_ij B_j from the rows already updated and sets B_i. So the numbers
// do not depend on how the rows are split into ranges. The lower sums kept from the
// previous sweep make the residual of the current B exact for free.
#include "solver/solve/methods.h"
#include "solver/solve/stopping.h"

namespace radflux {
namespace {

// The per-row vectors of a sweep.
struct SweepState {
  std::vector<Rgb> lower, upper;  // sum_{j<i} F_ij B_j and sum_{j>=i} F_ij B_j per lane
  std::vector<Rgb> r, reflected;  // residual and rho F B of B at the sweep's start
};

// One sweep.
absl::Status Sweep(const BandSystem& bands, std::vector<Rgb>& b, SweepState& st) {
  std::vector<Rgb>& lower = st.lower;
  std::vector<Rgb>& upper = st.upper;
  return ForEachRowRange(bands, [&](const RowsView& rows) {
    ParallelFor(rows.RowCount(), kSolveBlock, bands.threads, [&](int64_t begin, int64_t end) {
      for (int64_t l = begin; l < end; ++l) {
        const uint32_t i = rows.first_row + static_cast<uint32_t>(l);
        upper[i] = GatherRow(bands, rows, i, b, i, bands.n);
        for (int k = 0; k < bands.lanes; ++k) {
          st.reflected[i][k] = bands.rho[i][k] * (lower[i][k] + upper[i][k]);
          st.r[i][k] = bands.emission[i][k] + st.reflected[i][k] - b[i][k];
        }
      }
    });
    for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
      lower[i] = GatherRow(bands, rows, i, b, 0, i);
      for (int k = 0; k < bands.lanes; ++k)
        b[i][k] = bands.emission[i][k] + bands.rho[i][k] * (lower[i][k] + upper[i][k]);
    }
  });
}

}  // namespace

absl::Status SolveGaussSeidel(const BandSystem& bands, const SolverOptions& options,
                              const SolveCallback& callback, std::vector<Rgb>& b,
                              SolveResult& result) {
  IterationMonitor monitor(bands, options, callback, result);
  SweepState st{std::vector<Rgb>(bands.n), std::vector<Rgb>(bands.n), std::vector<Rgb>(bands.n),
                std::vector<Rgb>(bands.n)};
  absl::Status read = ForEachRowRange(bands, [&](const RowsView& rows) {
    ParallelFor(rows.RowCount(), kSolveBlock, bands.threads, [&](int64_t begin, int64_t end) {
      for (int64_t l = begin; l < end; ++l) {
        const uint32_t i = rows.first_row + static_cast<uint32_t>(l);
        st.lower[i] = GatherRow(bands, rows, i, b, 0, i);
      }
    });
  });
  while (read.ok() && !monitor.ShouldStop()) {
    read = Sweep(bands, b, st);
    if (!read.ok()) break;
    const double residual = MaxOverLanes(bands, ResidualMeasures(bands, st.r, st.reflected));
    if (monitor.Record(residual, residual, 0, b)) break;
  }
  return read;
}

}  // namespace radflux
