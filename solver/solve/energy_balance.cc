#include "solver/solve/energy_balance.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace radflux {
namespace {

bool HasRow(const PatchAttributes& p, uint32_t i) { return MaxComponent(p.reflectance[i]) > 0; }
bool Emits(const PatchAttributes& p, uint32_t i) { return MaxComponent(p.emission[i]) > 0; }

// Running sums of one pass over the rows.
struct BalancePass {
  std::vector<Rgb> arriving;    // power arriving per patch, W
  std::vector<Rgb> column_out;  // per row-less patch: its power the columns brought somewhere
  Rgb variance{};
};

// Row i (a patch with a row): its power along the row, the row-less patches' power along
// its columns, and the row's sampling variance.
void AddRow(const PatchAttributes& p, const std::vector<Rgb>& b, const RowsView& rows, uint32_t i,
            int sampled_rays, BalancePass& pass, EnergyBalance& out) {
  const auto cols = rows.RowCols(i);
  const auto vals = rows.RowValues(i);
  for (int band = 0; band < kBands; ++band) {
    const double outgoing = p.area[i] * b[i][band];
    double row_sum = 0, mean_w = 0, mean_w2 = 0;
    for (size_t e = 0; e < cols.size(); ++e) {
      const uint32_t j = cols[e];
      const double f = vals[e];
      pass.arriving[j][band] += outgoing * f;
      row_sum += f;
      if (!HasRow(p, j)) {
        const double gathered = p.area[i] * f * b[j][band];
        pass.arriving[i][band] += gathered;
        pass.column_out[j][band] += gathered;
      }
      if (sampled_rays > 0 && !Emits(p, j)) {
        const double w = p.reflectance[j][band] * b[i][band] - p.reflectance[i][band] * b[j][band];
        mean_w += f * w;
        mean_w2 += f * w * w;
      }
    }
    out.escaped[band] += outgoing * (1 - row_sum);
    if (sampled_rays > 0) {
      pass.variance[band] +=
          p.area[i] * p.area[i] / sampled_rays * std::max(0.0, mean_w2 - mean_w * mean_w);
    }
  }
}

}  // namespace

double EnergyBalance::RelativeImbalance() const {
  double worst = 0;
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] <= 0) continue;
    worst = std::max(worst, std::abs(emitted[b] - absorbed[b] - escaped[b]) / emitted[b]);
  }
  return worst;
}

double EnergyBalance::Tolerance() const {
  double worst = kEnergyBalanceFloor;
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] > 0) worst = std::max(worst, kEnergyBalanceSigmas * noise[b] / emitted[b]);
  }
  return worst;
}

bool EnergyBalance::Ok() const {
  for (int b = 0; b < kBands; ++b) {
    if (emitted[b] <= 0) continue;
    const double allowed =
        std::max(kEnergyBalanceFloor * emitted[b], kEnergyBalanceSigmas * noise[b]);
    if (!(std::abs(emitted[b] - absorbed[b] - escaped[b]) <= allowed)) return false;
  }
  return true;
}

absl::StatusOr<EnergyBalance> StreamEnergyBalance(const RadiositySystem& system,
                                                  const std::vector<Rgb>& radiosity,
                                                  int sampled_rays) {
  const PatchAttributes& p = *system.patches;
  EnergyBalance out;
  BalancePass pass{std::vector<Rgb>(p.size(), Rgb{}), std::vector<Rgb>(p.size(), Rgb{}), Rgb{}};
  const absl::Status read =
      ForEachRows(system.form_factors, system.row_store, [&](const RowsView& rows) {
        for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
          if (HasRow(p, i)) AddRow(p, radiosity, rows, i, sampled_rays, pass, out);
        }
      });
  if (!read.ok()) return read;
  for (uint32_t j = 0; j < p.size(); ++j) {
    for (int b = 0; b < kBands; ++b) {
      out.emitted[b] += p.area[j] * p.emission[j][b];
      out.absorbed[b] += (1 - p.reflectance[j][b]) * pass.arriving[j][b];
      if (!HasRow(p, j)) out.escaped[b] += p.area[j] * radiosity[j][b] - pass.column_out[j][b];
    }
  }
  for (int b = 0; b < kBands; ++b) out.noise[b] = std::sqrt(pass.variance[b]);
  return out;
}

EnergyBalance ComputeEnergyBalance(const RadiositySystem& system, const std::vector<Rgb>& radiosity,
                                   int sampled_rays) {
  assert(system.form_factors != nullptr);
  return *StreamEnergyBalance(system, radiosity, sampled_rays);
}

}  // namespace radflux
