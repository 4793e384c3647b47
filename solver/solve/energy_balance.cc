#include "solver/solve/energy_balance.h"

#include <algorithm>
#include <cassert>
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

absl::StatusOr<EnergyBalance> StreamEnergyBalance(const RadiositySystem& system,
                                                  const std::vector<Rgb>& radiosity) {
  const PatchAttributes& p = *system.patches;
  EnergyBalance out;
  std::vector<Rgb> arriving(p.size(), Rgb{});
  const absl::Status read =
      ForEachRows(system.form_factors, system.row_store, [&](const RowsView& rows) {
        for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
          const auto cols = rows.RowCols(i);
          const auto vals = rows.RowValues(i);
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
      });
  if (!read.ok()) return read;
  for (uint32_t j = 0; j < p.size(); ++j) {
    for (int b = 0; b < kBands; ++b) out.absorbed[b] += (1 - p.reflectance[j][b]) * arriving[j][b];
  }
  return out;
}

EnergyBalance ComputeEnergyBalance(const RadiositySystem& system,
                                   const std::vector<Rgb>& radiosity) {
  assert(system.form_factors != nullptr);
  return *StreamEnergyBalance(system, radiosity);
}

}  // namespace radflux
