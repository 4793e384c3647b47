#include "solver/solve/band_system.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace radflux {

BandSystem MakeBandSystem(const RadiositySystem& system, int threads) {
  const PatchAttributes& p = *system.patches;
  BandSystem bands;
  bands.f = system.form_factors;
  bands.store = system.row_store;
  bands.n = static_cast<uint32_t>(p.size());
  bands.area = &p.area;
  bands.threads = threads;
  bands.grey = p.grey;
  const int candidates = p.grey ? 1 : kBands;
  for (int band = 0; band < candidates; ++band) {
    double norm2 = 0;
    for (uint32_t i = 0; i < bands.n; ++i)
      norm2 += p.area[i] * p.emission[i][band] * p.emission[i][band];
    if (norm2 <= 0) continue;  // nothing emits in this band: B = 0 there
    bands.emission_norm[bands.lanes] = std::sqrt(norm2);
    bands.band[bands.lanes++] = band;
  }
  bands.rho.assign(bands.n, Rgb{});
  bands.emission.assign(bands.n, Rgb{});
  for (uint32_t i = 0; i < bands.n; ++i) {
    bands.total_area += p.area[i];
    for (int k = 0; k < bands.lanes; ++k) {
      bands.rho[i][k] = p.reflectance[i][bands.band[k]];
      bands.emission[i][k] = p.emission[i][bands.band[k]];
    }
  }
  return bands;
}

std::vector<Rgb> PackLanes(const BandSystem& bands, const std::vector<Rgb>& rgb) {
  std::vector<Rgb> lanes(bands.n, Rgb{});
  for (uint32_t i = 0; i < bands.n; ++i)
    for (int k = 0; k < bands.lanes; ++k) lanes[i][k] = rgb[i][bands.band[k]];
  return lanes;
}

void UnpackLanes(const BandSystem& bands, const std::vector<Rgb>& lanes, std::vector<Rgb>& rgb) {
  rgb.assign(bands.n, Rgb{});
  const bool grey = bands.grey && bands.lanes == 1;
  for (uint32_t i = 0; i < bands.n; ++i) {
    if (grey) {
      rgb[i].fill(lanes[i][0]);
      continue;
    }
    for (int k = 0; k < bands.lanes; ++k) rgb[i][bands.band[k]] = lanes[i][k];
  }
}

Rgb AreaDot(const BandSystem& bands, const std::vector<Rgb>& x, const std::vector<Rgb>& y) {
  const std::vector<double>& area = *bands.area;
  return ReduceBlocks(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
    Rgb s{};
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k) s[k] += area[i] * x[i][k] * y[i][k];
    return s;
  });
}

absl::Status ForEachRowRange(const BandSystem& bands, const RowsFn& fn) {
  return ForEachRows(bands.f, bands.store, fn);
}

Rgb GatherRow(const BandSystem& bands, const RowsView& rows, uint32_t i, const std::vector<Rgb>& x,
              uint32_t col_begin, uint32_t col_end) {
  const auto cols = rows.RowCols(i);
  const auto values = rows.RowValues(i);
  size_t e =
      static_cast<size_t>(std::lower_bound(cols.begin(), cols.end(), col_begin) - cols.begin());
  Rgb s{};
  if (bands.lanes == kBands) {  // the common case, unrolled: the same sums per lane
    for (; e < cols.size() && cols[e] < col_end; ++e) {
      const double fij = values[e];
      const Rgb& xj = x[cols[e]];
      s[0] += fij * xj[0];
      s[1] += fij * xj[1];
      s[2] += fij * xj[2];
    }
    return s;
  }
  for (; e < cols.size() && cols[e] < col_end; ++e) {
    const double fij = values[e];
    const Rgb& xj = x[cols[e]];
    for (int k = 0; k < bands.lanes; ++k) s[k] += fij * xj[k];
  }
  return s;
}

Rgb ResidualMeasures(const BandSystem& bands, const std::vector<Rgb>& r,
                     const std::vector<Rgb>& reflected) {
  // Serial, so a sweep pays for no extra parallel region (O(n), small next to the rows),
  // and summed exactly as ReduceBlocks(kSolveBlock) would: per block, then blocks in order.
  const std::vector<double>& area = *bands.area;
  Rgb r2{}, reflected2{};
  for (int64_t begin = 0; begin < bands.n; begin += kSolveBlock) {
    const int64_t end = std::min<int64_t>(bands.n, begin + kSolveBlock);
    Rgb s{}, t{};
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k) {
        s[k] += area[i] * r[i][k] * r[i][k];
        t[k] += area[i] * reflected[i][k] * reflected[i][k];
      }
    for (int k = 0; k < kBands; ++k) {
      r2[k] += s[k];
      reflected2[k] += t[k];
    }
  }
  Rgb measure{};
  for (int k = 0; k < bands.lanes; ++k) {
    const double scale = reflected2[k] > 0 ? std::sqrt(reflected2[k]) : bands.emission_norm[k];
    measure[k] = std::sqrt(r2[k]) / scale;
  }
  return measure;
}

absl::StatusOr<Rgb> LaneResiduals(const BandSystem& bands, const std::vector<Rgb>& b,
                                  std::vector<Rgb>* r) {
  std::vector<Rgb> local;
  std::vector<Rgb>& res = r != nullptr ? *r : local;
  res.resize(bands.n);
  std::vector<Rgb> reflected(bands.n);
  const absl::Status read = ForEachRowRange(bands, [&](const RowsView& rows) {
    ParallelFor(rows.RowCount(), kSolveBlock, bands.threads, [&](int64_t begin, int64_t end) {
      for (int64_t l = begin; l < end; ++l) {
        const uint32_t i = rows.first_row + static_cast<uint32_t>(l);
        const Rgb fb = GatherRow(bands, rows, i, b, 0, bands.n);
        Rgb ri{}, reflected_i{};
        for (int k = 0; k < bands.lanes; ++k) {
          reflected_i[k] = bands.rho[i][k] * fb[k];
          ri[k] = bands.emission[i][k] + reflected_i[k] - b[i][k];
        }
        res[i] = ri;
        reflected[i] = reflected_i;
      }
    });
  });
  if (!read.ok()) return read;
  return ResidualMeasures(bands, res, reflected);
}

Rgb ResidentLaneResiduals(const BandSystem& bands, const std::vector<Rgb>& b, std::vector<Rgb>* r) {
  assert(bands.f != nullptr);
  return *LaneResiduals(bands, b, r);
}

absl::StatusOr<double> MaxReflectedRowSum(const BandSystem& bands) {
  std::vector<double> row_q(bands.n, 0.0);
  const absl::Status read = ForEachRowRange(bands, [&](const RowsView& rows) {
    for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
      double sum = 0;
      for (const float v : rows.RowValues(i)) sum += v;
      for (int k = 0; k < bands.lanes; ++k) row_q[i] = std::max(row_q[i], bands.rho[i][k] * sum);
    }
  });
  if (!read.ok()) return read;
  return row_q.empty() ? 0.0 : *std::max_element(row_q.begin(), row_q.end());
}

Rgb MaxNorms(const BandSystem& bands, const std::vector<Rgb>& x) {
  Rgb m{};
  for (const Rgb& xi : x)
    for (int k = 0; k < bands.lanes; ++k) m[k] = std::max(m[k], std::abs(xi[k]));
  return m;
}

double MaxOverLanes(const BandSystem& bands, const Rgb& v) {
  double m = 0;
  for (int k = 0; k < bands.lanes; ++k) m = std::max(m, v[k]);
  return m;
}

}  // namespace radflux
