#include "solver/solve/energy_balance.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#include "absl/strings/str_format.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

bool HasRow(const PatchAttributes& p, uint32_t i) { return MaxComponent(p.reflectance[i]) > 0; }
bool Emits(const PatchAttributes& p, uint32_t i) { return MaxComponent(p.emission[i]) > 0; }

// Running sums of one pass over the rows.
struct BalancePass {
  std::vector<Rgb> arriving;    // power arriving per patch, W
  std::vector<Rgb> column_out;  // per row-less patch: its power the columns brought somewhere
  std::vector<Rgb> pairs;       // per patch: the imbalance of the emitter pairs it holds, W
  Rgb variance{};               // the multinomial reading of the rows' cosine rays, W^2
  Rgb pairs_ray_variance{};     // the part of sum pairs^2 the emitters' cosine rays explain
};

// The slot of `pairs` that holds pair {i, j} with an emitting patch among them (both with
// rows): the non-emitting one, or the lower index when both emit; none (-1) otherwise.
int64_t PairSlot(const PatchAttributes& p, uint32_t i, uint32_t j) {
  if (!HasRow(p, j)) return -1;
  const bool ei = Emits(p, i), ej = Emits(p, j);
  if (ei && ej) return std::min(i, j);
  if (ei != ej) return ei ? j : i;
  return -1;
}

// Whether the pair {i, j} exchanges power exactly both ways (RowSampling::reciprocal).
bool Exact(const PatchAttributes& p, const RowSampling& sampling, double mean_row_area, uint32_t i,
           uint32_t j) {
  if (sampling.reciprocal.empty() || sampling.reciprocal[i] == sampling.reciprocal[j]) {
    return false;
  }
  const uint32_t hidden = sampling.reciprocal[i] ? i : j, other = hidden == i ? j : i;
  return ReadFromHiddenRow(sampling.rays, p.area[other], Emits(p, other), p.area[hidden],
                           mean_row_area);
}

// Row i (a patch with a row): its power along the row, the row-less patches' power along
// its columns, its cosine rays' multinomial variance and its emitter pairs' imbalance.
void AddRow(const PatchAttributes& p, const std::vector<Rgb>& b, const RowsView& rows, uint32_t i,
            const RowSampling& sampling, double mean_row_area, BalancePass& pass,
            EnergyBalance& out) {
  const double rays =
      sampling.rays > 0 ? RowRayCount(sampling.rays, p.area[i], mean_row_area, Emits(p, i)) : 0;
  const auto cols = rows.RowCols(i);
  const auto vals = rows.RowValues(i);
  // Per band as below, entry by entry: each band's sums take the entries in the same order.
  Rgb outgoing{}, row_sum{}, mean_w{}, mean_w2{};
  for (int band = 0; band < kBands; ++band) outgoing[band] = p.area[i] * b[i][band];
  for (size_t e = 0; e < cols.size(); ++e) {
    const uint32_t j = cols[e];
    const double f = vals[e];
    const bool row_less = !HasRow(p, j);
    const bool exact = Exact(p, sampling, mean_row_area, i, j);
    const bool emits = Emits(p, j);
    const int64_t slot = !exact && sampling.light_samples > 0 ? PairSlot(p, i, j) : -1;
    for (int band = 0; band < kBands; ++band) {
      pass.arriving[j][band] += outgoing[band] * f;
      row_sum[band] += f;
      if (row_less) {
        const double gathered = p.area[i] * f * b[j][band];
        pass.arriving[i][band] += gathered;
        pass.column_out[j][band] += gathered;
      }
      if (exact) continue;
      const double w = p.reflectance[j][band] * b[i][band] - p.reflectance[i][band] * b[j][band];
      if (!emits) {
        mean_w[band] += f * w;
        mean_w2[band] += f * w * w;
      }
      if (slot < 0) continue;
      const double term = p.area[i] * f * w;
      pass.pairs[static_cast<size_t>(slot)][band] += term;
      if (!emits && rays > 0 && f < 1)
        pass.pairs_ray_variance[band] += term * term * (1 - f) / (f * rays);
    }
  }
  for (int band = 0; band < kBands; ++band) {
    out.escaped[band] += outgoing[band] * (1 - row_sum[band]);
    if (rays > 0) {
      pass.variance[band] +=
          p.area[i] * p.area[i] / rays * std::max(0.0, mean_w2[band] - mean_w[band] * mean_w[band]);
    }
  }
}

}  // namespace

double EnergyBalance::RelativeImbalance() const {
  double worst = 0;
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] <= 0) continue;
    worst = std::max(worst, std::abs(Imbalance(b)) / emitted[b]);
  }
  return worst;
}

double EnergyBalance::RelativeScaledOff() const {
  double worst = 0;
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] > 0) worst = std::max(worst, scaled_off[b] / emitted[b]);
  }
  return worst;
}

double EnergyBalance::Tolerance() const {
  double worst = kEnergyBalanceFloor;
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] > 0) worst = std::max(worst, kEnergyBalanceSigmas * noise[b] / emitted[b]);
  }
  return std::min(worst, kEnergyBalanceCeiling);
}

bool EnergyBalance::Ok() const {
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] <= 0) continue;
    const double allowed =
        std::min(kEnergyBalanceCeiling * emitted[b],
                 std::max(kEnergyBalanceFloor * emitted[b], kEnergyBalanceSigmas * noise[b]));
    if (!(std::abs(Imbalance(b)) <= allowed)) return false;
    if (!(scaled_off[b] <= allowed)) return false;
  }
  return true;
}

std::string EnergyBalance::Why() const {
  double imbalance = 0;
  if (RelativeScaledOff() > Tolerance()) {
    return absl::StrFormat(
        "the row-sum cap removed %.2f%% of the emitted power: rows near emitters too noisy for "
        "their reflectance (more --rays or --samples)",
        100 * RelativeScaledOff());
  }
  for (int b = 0; b < kBands; ++b) {
    if (escaped[b] < -kEnergyBalanceFloor * emitted[b]) {
      return "escaped is negative: rows or emitter columns carry more than the power that "
             "leaves a patch (overlapping or coincident faces counted twice, row sums above 1)";
    }
    imbalance += Imbalance(b);
  }
  return imbalance > 0
             ? "absorbed + escaped fall short of emitted: light the rows lose (rows that are "
               "not reciprocal, e.g. emitter columns against the emitters' own rows, or a "
               "solve that has not converged)"
             : "absorbed + escaped exceed emitted: rows that carry more than they should "
               "(row sums above 1, rows that are not reciprocal, coplanar faces that overlap)";
}

std::string EnergyBalance::OffMessage() const {
  if (Ok()) return "";
  return absl::StrFormat("energy balance off by %.2f%% of the emitted power (tolerance %.2f%%): %s",
                         100 * RelativeImbalance(), 100 * Tolerance(), Why());
}

absl::StatusOr<EnergyBalance> StreamEnergyBalance(const RadiositySystem& system,
                                                  const std::vector<Rgb>& radiosity,
                                                  const RowSampling& sampling,
                                                  std::span<const ScaledRow> scaled_off,
                                                  std::span<const Rgb> detail) {
  const PatchAttributes& p = *system.patches;
  EnergyBalance out;
  BalancePass pass{std::vector<Rgb>(p.size(), Rgb{}), std::vector<Rgb>(p.size(), Rgb{}),
                   std::vector<Rgb>(p.size(), Rgb{}), Rgb{}};
  std::vector<uint8_t> has_row(p.size());
  for (uint32_t i = 0; i < p.size(); ++i) has_row[i] = HasRow(p, i);
  const double mean_row_area = MeanRowArea(p.area, has_row);
  const absl::Status read =
      ForEachRows(system.form_factors, system.row_store, [&](const RowsView& rows) {
        for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
          if (has_row[i]) AddRow(p, radiosity, rows, i, sampling, mean_row_area, pass, out);
        }
      });
  if (!read.ok()) return read;
  Rgb pairs_square{};
  for (uint32_t j = 0; j < detail.size() && j < p.size(); ++j) {
    for (int b = 0; b < kBands; ++b) {
      pass.arriving[j][b] += p.area[j] * detail[j][b];
      out.cell_detail[b] += p.area[j] * detail[j][b];
    }
  }
  for (uint32_t j = 0; j < p.size(); ++j) {
    for (int b = 0; b < kBands; ++b) {
      out.emitted[b] += p.area[j] * p.emission[j][b];
      out.absorbed[b] += (1 - p.reflectance[j][b]) * pass.arriving[j][b];
      if (!HasRow(p, j)) out.escaped[b] += p.area[j] * radiosity[j][b] - pass.column_out[j][b];
      pairs_square[b] += pass.pairs[j][b] * pass.pairs[j][b];
    }
  }
  // The cap's removed sums are part of 1 - row_sum above; booked apart.
  for (const ScaledRow& scaled : scaled_off) {
    if (scaled.row >= p.size() || !has_row[scaled.row]) continue;
    for (int b = 0; b < kBands; ++b) {
      const double power = p.area[scaled.row] * radiosity[scaled.row][b] * scaled.removed;
      out.scaled_off[b] += power;
      out.escaped[b] -= power;
    }
  }
  for (int b = 0; b < kBands; ++b) {
    const double light = std::max(0.0, pairs_square[b] - pass.pairs_ray_variance[b]);
    out.noise[b] = std::sqrt(pass.variance[b] + light);
  }
  return out;
}

EnergyBalance ComputeEnergyBalance(const RadiositySystem& system, const std::vector<Rgb>& radiosity,
                                   const RowSampling& sampling,
                                   std::span<const ScaledRow> scaled_off) {
  assert(system.form_factors != nullptr);
  return *StreamEnergyBalance(system, radiosity, sampling, scaled_off);
}

}  // namespace radflux
