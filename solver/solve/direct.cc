// Direct: dense LU with partial pivoting of M = I - diag(rho) F in double precision.
// Lanes with identical reflectance share one factorization. The elimination of each
// pivot column is parallel over rows; every row is updated by exactly one thread, so
// the result does not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/strings/str_cat.h"
#include "solver/solve/methods.h"
#include "solver/solve/stopping.h"

namespace radflux {
namespace {

constexpr uint32_t kCancelCheckEvery = 32;   // pivots between cancellation checks
constexpr int64_t kMinBlockFlops = 1 << 16;  // per ParallelFor block of row updates

struct DenseLu {
  uint32_t n = 0;
  std::vector<double> a;        // row-major n x n: L (unit, below) and U (on and above)
  std::vector<uint32_t> pivot;  // row swapped with row k at step k
};

// M = I - diag(rho_k) F for lane k.
DenseLu BuildMatrix(const BandSystem& bands, int lane) {
  DenseLu lu;
  lu.n = bands.n;
  lu.a.assign(static_cast<size_t>(bands.n) * bands.n, 0.0);
  lu.pivot.assign(bands.n, 0);
  for (uint32_t i = 0; i < bands.n; ++i) {
    double* row = &lu.a[static_cast<size_t>(i) * bands.n];
    const auto cols = bands.f->RowCols(i);
    const auto values = bands.f->RowValues(i);
    for (size_t e = 0; e < cols.size(); ++e) row[cols[e]] -= bands.rho[i][lane] * values[e];
    row[i] += 1.0;
  }
  return lu;
}

// Factors in place; false when cancelled. FAILED_PRECONDITION when singular.
absl::StatusOr<bool> Factor(DenseLu& lu, const SolverOptions& options, int threads) {
  const uint32_t n = lu.n;
  for (uint32_t k = 0; k < n; ++k) {
    if (k % kCancelCheckEvery == 0 && options.cancel != nullptr && options.cancel->load()) {
      return false;
    }
    uint32_t p = k;
    for (uint32_t i = k + 1; i < n; ++i) {
      if (std::abs(lu.a[size_t{i} * n + k]) > std::abs(lu.a[size_t{p} * n + k])) p = i;
    }
    const double pivot = lu.a[size_t{p} * n + k];
    if (pivot == 0) {
      return absl::FailedPreconditionError(absl::StrCat("direct: singular system at column ", k,
                                                        " (a closed scene with reflectance 1?)"));
    }
    lu.pivot[k] = p;
    if (p != k) {
      for (uint32_t j = 0; j < n; ++j) std::swap(lu.a[size_t{k} * n + j], lu.a[size_t{p} * n + j]);
    }
    const double* row_k = &lu.a[size_t{k} * n];
    const int64_t rows_per_block = std::max<int64_t>(16, kMinBlockFlops / (n - k));
    ParallelFor(n - k - 1, rows_per_block, threads, [&](int64_t begin, int64_t end) {
      for (int64_t r = begin; r < end; ++r) {
        double* row = &lu.a[(size_t{k} + 1 + static_cast<size_t>(r)) * n];
        const double l = row[k] / pivot;
        row[k] = l;
        for (uint32_t j = k + 1; j < n; ++j) row[j] -= l * row_k[j];
      }
    });
  }
  return true;
}

// Solves M x = E for lane `lane` of `b` with the factors.
void SolveLane(const DenseLu& lu, const BandSystem& bands, int lane, std::vector<Rgb>& b) {
  const uint32_t n = lu.n;
  std::vector<double> x(n);
  for (uint32_t i = 0; i < n; ++i) x[i] = bands.emission[i][lane];
  for (uint32_t k = 0; k < n; ++k) std::swap(x[k], x[lu.pivot[k]]);
  for (uint32_t i = 0; i < n; ++i) {
    double s = x[i];
    for (uint32_t j = 0; j < i; ++j) s -= lu.a[size_t{i} * n + j] * x[j];
    x[i] = s;
  }
  for (uint32_t i = n; i-- > 0;) {
    double s = x[i];
    for (uint32_t j = i + 1; j < n; ++j) s -= lu.a[size_t{i} * n + j] * x[j];
    x[i] = s / lu.a[size_t{i} * n + i];
  }
  for (uint32_t i = 0; i < n; ++i) b[i][lane] = x[i];
}

bool SameReflectance(const BandSystem& bands, int k, int l) {
  for (uint32_t i = 0; i < bands.n; ++i) {
    if (bands.rho[i][k] != bands.rho[i][l]) return false;
  }
  return true;
}

}  // namespace

absl::Status SolveDirect(const BandSystem& bands, const SolverOptions& options,
                         const SolveCallback& callback, std::vector<Rgb>& b, SolveResult& result) {
  if (bands.n > kMaxDirectPatches) {
    return absl::ResourceExhaustedError(
        absl::StrCat("direct solver refuses ", bands.n, " patches (limit ", kMaxDirectPatches,
                     ": dense LU needs n^2 doubles and n^3/3 flops); use cg"));
  }
  IterationMonitor monitor(bands, options, callback, result);
  if (monitor.ShouldStop()) return absl::OkStatus();
  std::vector<Rgb> x = b;
  std::array<bool, kBands> done{};
  for (int k = 0; k < bands.lanes; ++k) {
    if (done[k]) continue;
    DenseLu lu = BuildMatrix(bands, k);
    absl::StatusOr<bool> factored = Factor(lu, options, bands.threads);
    if (!factored.ok()) return factored.status();
    if (!*factored) {
      result.cancelled = true;
      return absl::OkStatus();  // b keeps the start values
    }
    for (int l = k; l < bands.lanes; ++l) {
      if (done[l] || !SameReflectance(bands, k, l)) continue;
      SolveLane(lu, bands, l, x);
      done[l] = true;
    }
  }
  b = std::move(x);
  const double residual = MaxOverLanes(bands, ResidentLaneResiduals(bands, b, nullptr));
  monitor.Record(residual, residual, 0, b);
  return absl::OkStatus();
}

}  // namespace radflux
