// Energy bookkeeping of a solution, per band: the power the emitters put in must leave
// as absorbed power plus power escaping through openings (emitted = absorbed + escaped).
// Patches without a row (rho = 0) count their outgoing power as unaccounted.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/solve/solver.h"

namespace radflux {

struct EnergyBalance {
  Rgb emitted{};      // sum A_i E_i, W per band (scene units^2 * W/m^2)
  Rgb absorbed{};     // sum_j (1 - rho_j) * power arriving at j
  Rgb escaped{};      // sum_i A_i B_i (1 - sum_j F_ij) over patches with rows
  Rgb unaccounted{};  // outgoing power of row-less patches (rho = 0)
  // |emitted - absorbed - escaped - unaccounted| / emitted, max over emitting bands.
  double RelativeImbalance() const;
};

// The balance of `radiosity`, reading the rows once in order (streamed when the system's
// rows are in a row store: then its read error).
absl::StatusOr<EnergyBalance> StreamEnergyBalance(const RadiositySystem& system,
                                                  const std::vector<Rgb>& radiosity);
// The same for rows in memory (system.form_factors), which cannot fail.
EnergyBalance ComputeEnergyBalance(const RadiositySystem& system,
                                   const std::vector<Rgb>& radiosity);

}  // namespace radflux
