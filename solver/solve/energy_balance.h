// Energy bookkeeping of a solution, per band: the power the emitters put in must leave
// as absorbed power plus power escaping through openings (emitted = absorbed + escaped).
// Light leaves a patch with a row along that row (A_i B_i F_ij reaches j); a patch without
// a row (rho = 0 in every band, e.g. a lamp with Kd = 0) is seen through the other rows'
// columns instead (A_j F_ji B_i reaches j, by reciprocity), so its power is accounted too.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/formfactor/row_accumulator.h"
#include "solver/solve/solver.h"

namespace radflux {

// The imbalance "ok" threshold never goes below this fraction of the emitted power (the
// analytic and hemicube rows' discretisation, float storage).
inline constexpr double kEnergyBalanceFloor = 0.005;
// Multiples of EnergyBalance::noise the imbalance may reach. noise is a calibrated estimate
// of the imbalance's standard deviation over seeds (at the defaults: office2 1.88% measured
// over 20 seeds against 2.02% estimated, imbalance / noise with a spread of 0.92; the
// conference room's groups 1.0 over 8 seeds), so 3 lets a correct solve through but for
// about 3 seeds in 1,000.
inline constexpr double kEnergyBalanceSigmas = 3;
// An imbalance above this fraction is never ok, however noisy the rows: a 3-sigma band that
// wide no longer vouches for the solution (the conference room's heavy-tailed seed 3 at the
// defaults: 13.4% off against a 20.8% band, its floor 85% too bright).
inline constexpr double kEnergyBalanceCeiling = 0.10;

struct EnergyBalance {
  Rgb emitted{};   // sum A_i E_i, W per band (scene units^2 * W/m^2)
  Rgb absorbed{};  // sum_j (1 - rho_j) * power arriving at j
  Rgb escaped{};   // power leaving that no row or column brings anywhere (openings, cut-off)
  // Power the row-sum cap removed (RowContext::MaxRowSum): sum over the rows it scaled back of
  // A_i B_i times the sum it removed, W per band. Not light that escapes: the rows' noise
  // above the cap, cut off, so B is that much low (a bias, where the rest is noise). So the
  // books read emitted = absorbed + escaped + scaled_off, and a balance is ok only when
  // scaled_off too is within the tolerance.
  Rgb scaled_off{};
  // A grouped solve's second source (cell_detail.h): the power its cells' direct light, brighter
  // or darker than their group's B, brings to the unknowns with rows beyond what the groups'
  // B brings (sum_i A_i H_i, absorbed and reflected as any arriving power), W per band; 0
  // without cells. Redistributed, not emitted: the books read emitted + cell_detail =
  // absorbed + escaped + scaled_off.
  Rgb cell_detail{};
  // emitted + cell_detail - absorbed - escaped - scaled_off in band b.
  double Imbalance(int b) const {
    return emitted[b] + cell_detail[b] - absorbed[b] - escaped[b] - scaled_off[b];
  }
  // Standard deviation of emitted - absorbed - escaped that the rows' Monte Carlo noise
  // alone gives (0 for rows that are not sampled), per band, W. At the solution the
  // imbalance is sum_ij A_i F_ij (rho_j B_i - rho_i B_j) = sum_ij A_i F_ij w_ij, zero for
  // reciprocal rows and zero in expectation for unbiased ones (no bias in it: office2's mean
  // over 20 seeds is -0.06% +- 0.42% of the emitted power at k = 64). Two parts:
  //  - the cosine rays: each sampled row's non-emitter columns are a multinomial draw of k
  //    rays (misses carry no noise), var_i = A_i^2 / k (sum_j F_ij w_ij^2 - (sum_j F_ij
  //    w_ij)^2), summed over rows (an upper estimate for stratified rows);
  //  - the light samples, whose spread depends on shadows and on how a group's members face
  //    the emitters, so it is measured, not modelled: each pair of a patch j and an emitting
  //    patch e has two independent estimates of one power, A_j F_je (light-sampled) and
  //    A_e F_ej (e's cosine rays); D_j, the imbalance of j's pairs, has mean 0, and sum_j
  //    D_j^2 less the part the emitters' rays explain (sum (A_e F_ej w)^2 (1 - F_ej) /
  //    (F_ej k)) estimates the light samples' variance.
  Rgb noise{};
  // |Imbalance| / emitted, max over emitting bands.
  double RelativeImbalance() const;
  // scaled_off / emitted, max over emitting bands.
  double RelativeScaledOff() const;
  // The threshold for "ok": max(kEnergyBalanceFloor, kEnergyBalanceSigmas * noise / emitted),
  // the largest over emitting bands, never above kEnergyBalanceCeiling.
  double Tolerance() const;
  // Every emitting band's imbalance and scaled_off within its own threshold.
  bool Ok() const;
  // Which term of a balance that is not ok is out, and the likely why (one clause).
  std::string Why() const;
  // One line for a balance that is not ok: "energy balance off: absorbed + escaped exceed
  // emitted by 4.3% (tolerance 0.5%): <Why()>"; empty when it is ok.
  std::string OffMessage() const;
};

// How the rows were sampled, for EnergyBalance::noise: both 0 for rows that are not.
struct RowSampling {
  int rays = 0;           // k of Monte Carlo rows: row i's non-emitter entries are hits / k_i,
                          // k_i = RowRayCount(k, area_i, mean row area) (row_rays.h)
  int light_samples = 0;  // light samples behind a row's emitter columns (0: not sampled)
  // Per unknown (empty: none), 1 where the other rows' entries towards it are its own row's by
  // reciprocity (A_i F_ij = A_j F_ji: monte_carlo's hidden unknowns, reciprocal_columns.h)
  // when ReadFromHiddenRow (row_rays.h) says so: such a pair exchanges power exactly, so
  // adds no noise.
  std::vector<uint8_t> reciprocal = {};
};

// The balance of `radiosity`, reading the rows once in order (streamed when the system's
// rows are in a row store: then its read error); `scaled_off`: the rows the row-sum cap
// scaled back (RowBlockStats::scaled_off), booked as EnergyBalance::scaled_off; `detail`: H
// per unknown when the solve had the cells' detail as a source (cell_detail.h), else empty.
absl::StatusOr<EnergyBalance> StreamEnergyBalance(const RadiositySystem& system,
                                                  const std::vector<Rgb>& radiosity,
                                                  const RowSampling& sampling = {},
                                                  std::span<const ScaledRow> scaled_off = {},
                                                  std::span<const Rgb> detail = {});
// The same for rows in memory (system.form_factors), which cannot fail.
EnergyBalance ComputeEnergyBalance(const RadiositySystem& system, const std::vector<Rgb>& radiosity,
                                   const RowSampling& sampling = {},
                                   std::span<const ScaledRow> scaled_off = {});

}  // namespace radflux
