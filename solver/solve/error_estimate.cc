#include "solver/solve/error_estimate.h"

#include <algorithm>
#include <cmath>

namespace radflux {
namespace {

// Iterations over which the contraction rate is averaged.
constexpr size_t kRateWindow = 10;

// Geometric mean ratio of the last kRateWindow measures (or fewer); NaN without two.
double ContractionRate(const std::vector<double>& history) {
  if (history.size() < 2) return std::nan("");
  const size_t m = std::min(kRateWindow, history.size() - 1);
  const double first = history[history.size() - 1 - m], last = history.back();
  if (!(first > 0) || !(last > 0)) return std::nan("");
  return std::pow(last / first, 1.0 / static_cast<double>(m));
}

}  // namespace

absl::Status EstimateError(const BandSystem& bands, const std::vector<Rgb>& b,
                           const std::vector<Rgb>& r, SolveResult& result) {
  const absl::StatusOr<double> q = MaxReflectedRowSum(bands);
  if (!q.ok()) return q.status();
  if (*q < 1) {
    std::vector<Rgb> reflected(b.size());
    for (size_t i = 0; i < b.size(); ++i)
      for (int k = 0; k < bands.lanes; ++k) reflected[i][k] = b[i][k] - bands.emission[i][k];
    const Rgb r_max = MaxNorms(bands, r), reflected_max = MaxNorms(bands, reflected);
    double estimate = 0;
    for (int k = 0; k < bands.lanes; ++k) {
      if (r_max[k] == 0) continue;
      const double scale = reflected_max[k] > 0 ? reflected_max[k] : MaxNorms(bands, b)[k];
      estimate = std::max(estimate, r_max[k] / (1 - *q) / scale);
    }
    result.error_estimate = estimate;
    result.error_estimate_method = "bound";
    return absl::OkStatus();
  }
  const double c = ContractionRate(result.residual_history);
  if (c < 1) {
    result.error_estimate = result.residual / (1 - c);
    result.error_estimate_method = "rate";
  } else {
    result.error_estimate = std::nan("");
    result.error_estimate_method = "";
  }
  return absl::OkStatus();
}

}  // namespace radflux
