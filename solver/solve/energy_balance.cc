#include "solver/solve/energy_balance.h"

#include <algorithm>
#include <cmath>

namespace radflux {

double EnergyBalance::RelativeImbalance() const {
  double worst = 0;
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] <= 0) continue;
    const double diff = emitted[b] - absorbed[b] - escaped[b] - unaccounted[b];
    worst = std::max(worst, std::abs(diff) / emitted[b]);
  }
  return worst;
}

EnergyBalance ComputeEnergyBalance(const RadiositySystem& system,
                                   const std::vector<Rgb>& radiosity) {
  const CsrMatrix& f = *system.form_factors;
  const PatchAttributes& p = *system.patches;
  EnergyBalance out;
  std::vector<Rgb> arriving(p.size(), Rgb{});
  for (uint32_t i = 0; i < p.size(); ++i) {
    const auto cols = f.RowCols(i);
    const auto vals = f.RowValues(i);
    const bool has_row = MaxComponent(p.reflectance[i]) > 0;
    for (int b = 0; b < kBands; ++b) {
      const double outgoing = p.area[i] * radiosity[i][b];
      out.emitted[b] += p.area[i] * p.emission[i][b];
      if (!has_row) {
        out.unaccounted[b] += outgoing;
        continue;
      }
      double row_sum = 0;
      for (size_t k = 0; k < cols.size(); ++k) {
        arriving[cols[k]][b] += outgoing * vals[k];
        row_sum += vals[k];
      }
      out.escaped[b] += outgoing * (1 - row_sum);
    }
  }
  for (uint32_t j = 0; j < p.size(); ++j) {
    for (int b = 0; b < kBands; ++b) out.absorbed[b] += (1 - p.reflectance[j][b]) * arriving[j][b];
  }
  return out;
}

}  // namespace radflux
