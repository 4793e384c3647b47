#include "solver/formfactor/reciprocal_pairs.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "solver/core/parallel.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

constexpr int64_t kRowsPerBlock = 256;
constexpr uint32_t kNoColumn = std::numeric_limits<uint32_t>::max();

// One entry of a row being averaged: its column, value and whether it is an averaged pair's.
struct Entry {
  uint32_t col;
  double value;
  bool averaged;
};

}  // namespace

void AverageReciprocalPairs(const RowContext& context, int rays, std::span<const uint8_t> cosine,
                            int threads, CsrMatrix& rows) {
  const uint32_t n = rows.rows;
  std::vector<double> k(n), density(n);
  std::vector<uint8_t> takes_part(n, 0);
  for (uint32_t u = 0; u < n; ++u) {
    const double area = context.opaque_area[u];
    k[u] = RowRayCount(rays, area, context.mean_row_area);
    takes_part[u] = u < cosine.size() && cosine[u] && area > 0;
    density[u] = takes_part[u] ? k[u] / area : 0;
  }
  // The other rows' hits on each row i: (j, h_ji = k_j F_ji), ascending in j.
  std::vector<uint64_t> first(n + 1, 0);
  for (uint32_t j = 0; j < n; ++j) {
    if (!takes_part[j]) continue;
    for (uint32_t i : rows.RowCols(j)) {
      if (i != j && takes_part[i]) ++first[i + 1];
    }
  }
  for (uint32_t i = 0; i < n; ++i) first[i + 1] += first[i];
  std::vector<std::pair<uint32_t, float>> hits(first[n]);
  {
    std::vector<uint64_t> next(first.begin(), first.end() - 1);
    for (uint32_t j = 0; j < n; ++j) {
      if (!takes_part[j]) continue;
      const auto cols = rows.RowCols(j);
      const auto vals = rows.RowValues(j);
      for (size_t e = 0; e < cols.size(); ++e) {
        const uint32_t i = cols[e];
        if (i != j && takes_part[i]) hits[next[i]++] = {j, static_cast<float>(k[j] * vals[e])};
      }
    }
  }
  const int64_t block_count = (n + kRowsPerBlock - 1) / kRowsPerBlock;
  std::vector<RowBlock> blocks(static_cast<size_t>(block_count));
  ParallelFor(block_count, 1, threads, [&](int64_t begin, int64_t end) {
    std::vector<Entry> entries;
    for (int64_t b = begin; b < end; ++b) {
      RowBlock& block = blocks[static_cast<size_t>(b)];
      block.first_row = static_cast<uint32_t>(b * kRowsPerBlock);
      const uint32_t last = std::min<uint32_t>(n, block.first_row + kRowsPerBlock);
      for (uint32_t i = block.first_row; i < last; ++i) {
        const auto cols = rows.RowCols(i);
        const auto vals = rows.RowValues(i);
        entries.clear();
        double own_sum = 0, averaged_sum = 0;
        size_t a = 0;
        uint64_t h = first[i];
        while (a < cols.size() || h < first[i + 1]) {
          const uint32_t own_col = a < cols.size() ? cols[a] : kNoColumn;
          const uint32_t back_col = h < first[i + 1] ? hits[h].first : kNoColumn;
          const uint32_t j = std::min(own_col, back_col);
          const double own = own_col == j ? vals[a++] : 0.0;
          const double back = back_col == j ? hits[h++].second : 0.0;
          if (!(takes_part[i] && takes_part[j] && j != i)) {
            entries.push_back({j, own, false});
            continue;
          }
          const double v =
              (k[i] * own + back) / (context.opaque_area[i] * (density[i] + density[j]));
          own_sum += own;
          averaged_sum += v;
          entries.push_back({j, v, true});
        }
        const double scale = averaged_sum > 0 ? own_sum / averaged_sum : 0;
        for (const Entry& e : entries) {
          const double v = e.averaged ? e.value * scale : e.value;
          if (v > 0) block.Add(e.col, static_cast<float>(v));
        }
        block.EndRow();
      }
    }
  });
  CsrMatrix out;
  out.cols = rows.cols;
  size_t nnz = 0;
  for (const RowBlock& block : blocks) nnz += block.col.size();
  out.Reserve(n, nnz);
  for (RowBlock& block : blocks) {
    out.Append(block);
    block = RowBlock{};
  }
  rows = std::move(out);
}

}  // namespace radflux
