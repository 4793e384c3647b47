#include "solver/formfactor/enclosure_adjust.h"

#include <algorithm>
#include <cmath>

namespace radflux {

EnclosureError MeasureEnclosureError(const std::vector<std::vector<double>>& factor,
                                     const std::vector<double>& area) {
  EnclosureError e;
  const size_t n = factor.size();
  for (size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (size_t j = 0; j < n; ++j) {
      sum += factor[i][j];
      if (j <= i) continue;
      const double a = area[i] * factor[i][j], b = area[j] * factor[j][i];
      if (std::max(a, b) > 0) {
        e.max_reciprocity = std::max(e.max_reciprocity, std::abs(a - b) / std::max(a, b));
      }
    }
    e.max_closure = std::max(e.max_closure, std::abs(1 - sum));
    e.rms_closure += (1 - sum) * (1 - sum);
  }
  e.rms_closure = n ? std::sqrt(e.rms_closure / static_cast<double>(n)) : 0;
  return e;
}

EnclosureAdjustment AdjustEnclosure(std::vector<std::vector<double>>& factor,
                                    const std::vector<double>& area, double tolerance,
                                    int max_sweeps) {
  EnclosureAdjustment result;
  result.before = MeasureEnclosureError(factor, area);
  const size_t n = factor.size();
  // af[i][j] = A_i F_ij made symmetric.
  std::vector<std::vector<double>> af(n, std::vector<double>(n));
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j <= i; ++j) {
      af[i][j] = af[j][i] = 0.5 * (area[i] * factor[i][j] + area[j] * factor[j][i]);
    }
  }
  for (double worst = 1; result.sweeps < max_sweeps && worst > tolerance; ++result.sweeps) {
    worst = 0;
    for (size_t m = 0; m < n; ++m) {
      double sum = 0;
      for (size_t k = 0; k < n; ++k) sum += af[m][k];
      const double row = sum / area[m];
      if (row <= 0) continue;
      worst = std::max(worst, std::abs(row - 1));
      const double scale = 1 / row;
      for (size_t k = 0; k < n; ++k) {
        af[m][k] *= scale;
        if (k != m) af[k][m] *= scale;
      }
    }
    result.converged = worst <= tolerance;
  }
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) factor[i][j] = af[i][j] / area[i];
  }
  result.after = MeasureEnclosureError(factor, area);
  return result;
}

}  // namespace radflux
