#include "solver/formfactor/reciprocal_pairs.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "solver/core/parallel.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

constexpr uint32_t kRowsPerTask = 256;
constexpr uint32_t kNoColumn = std::numeric_limits<uint32_t>::max();

// One entry of a row being averaged: its column, value and whether it is an averaged pair's.
struct Entry {
  uint32_t col;
  double value;
  bool averaged;
};

// The other rows' hits on one row i, (j, h_ji = k_j F_ji), ascending in j.
using BackHit = std::pair<uint32_t, float>;

// Bytes a row takes in a range being averaged: its own entries and back hits, and offsets.
uint64_t RangeBytes(uint32_t own, uint32_t back) {
  return uint64_t{own} * (sizeof(uint32_t) + sizeof(float)) + uint64_t{back} * sizeof(BackHit) +
         2 * sizeof(uint64_t);
}

}  // namespace

ReciprocalPairs::ReciprocalPairs(const RowContext& context, int rays,
                                 std::span<const uint8_t> cosine) {
  const size_t n = context.opaque_area.size();
  area_ = context.opaque_area;
  rays_.resize(n);
  density_.resize(n);
  takes_part_.assign(n, 0);
  for (size_t u = 0; u < n; ++u) {
    rays_[u] = RowRayCount(rays, area_[u], context.mean_row_area);
    takes_part_[u] = u < cosine.size() && cosine[u] && area_[u] > 0;
    density_[u] = takes_part_[u] ? rays_[u] / area_[u] : 0;
  }
}

absl::Status ReciprocalPairs::Count(const CsrMatrix* matrix, const RowStore* store,
                                    std::vector<uint32_t>& own, std::vector<uint32_t>& back) const {
  own.assign(takes_part_.size(), 0);
  back.assign(takes_part_.size(), 0);
  return ForEachRows(matrix, store, [&](const RowsView& rows) {
    for (uint32_t j = rows.first_row; j < rows.EndRow(); ++j) {
      const auto cols = rows.RowCols(j);
      own[j] = static_cast<uint32_t>(cols.size());
      if (!takes_part_[j]) continue;
      for (uint32_t i : cols) {
        if (i != j && takes_part_[i]) ++back[i];
      }
    }
  });
}

absl::Status ReciprocalPairs::AverageRange(int threads, const CsrMatrix* matrix,
                                           const RowStore* store, std::span<const uint32_t> back,
                                           uint32_t first, uint32_t last, const Emit& emit) const {
  const uint32_t count = last - first;
  std::vector<uint64_t> begin(count + 1, 0);
  for (uint32_t r = 0; r < count; ++r) begin[r + 1] = begin[r] + back[first + r];
  std::vector<BackHit> hits(begin[count]);
  std::vector<uint64_t> next(begin.begin(), begin.end() - 1);
  RowBlock own_copy;  // rows [first, last) of a store
  own_copy.first_row = first;
  absl::Status read = ForEachRows(matrix, store, [&](const RowsView& rows) {
    for (uint32_t j = rows.first_row; j < rows.EndRow(); ++j) {
      const auto cols = rows.RowCols(j);
      const auto vals = rows.RowValues(j);
      if (matrix == nullptr && j >= first && j < last) {
        own_copy.col.insert(own_copy.col.end(), cols.begin(), cols.end());
        own_copy.value.insert(own_copy.value.end(), vals.begin(), vals.end());
        own_copy.EndRow();
      }
      if (!takes_part_[j]) continue;
      for (size_t e = std::lower_bound(cols.begin(), cols.end(), first) - cols.begin();
           e < cols.size() && cols[e] < last; ++e) {
        const uint32_t i = cols[e];
        if (i != j && takes_part_[i]) {
          hits[next[i - first]++] = {j, static_cast<float>(rays_[j] * vals[e])};
        }
      }
    }
  });
  if (!read.ok()) return read;
  const RowsView own = matrix != nullptr ? matrix->View() : own_copy.View();

  const int64_t task_count = (count + kRowsPerTask - 1) / kRowsPerTask;
  std::vector<RowBlock> blocks(static_cast<size_t>(task_count));
  ParallelFor(task_count, 1, threads, [&](int64_t begin_task, int64_t end_task) {
    std::vector<Entry> entries;
    for (int64_t t = begin_task; t < end_task; ++t) {
      RowBlock& block = blocks[static_cast<size_t>(t)];
      block.first_row = first + static_cast<uint32_t>(t) * kRowsPerTask;
      const uint32_t end = std::min(last, block.first_row + kRowsPerTask);
      for (uint32_t i = block.first_row; i < end; ++i) {
        const auto cols = own.RowCols(i);
        const auto vals = own.RowValues(i);
        entries.clear();
        double own_sum = 0, averaged_sum = 0;
        size_t a = 0;
        uint64_t h = begin[i - first];
        const uint64_t h_end = begin[i - first + 1];
        while (a < cols.size() || h < h_end) {
          const uint32_t own_col = a < cols.size() ? cols[a] : kNoColumn;
          const uint32_t back_col = h < h_end ? hits[h].first : kNoColumn;
          const uint32_t j = std::min(own_col, back_col);
          const double own_value = own_col == j ? vals[a++] : 0.0;
          const double back_value = back_col == j ? hits[h++].second : 0.0;
          if (!(takes_part_[i] && takes_part_[j] && j != i)) {
            entries.push_back({j, own_value, false});
            continue;
          }
          const double v =
              (rays_[i] * own_value + back_value) / (area_[i] * (density_[i] + density_[j]));
          own_sum += own_value;
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
  return emit(blocks);
}

void ReciprocalPairs::Average(int threads, CsrMatrix& rows) const {
  std::vector<uint32_t> own, back;
  (void)Count(&rows, nullptr, own, back);  // rows in memory: nothing to fail
  CsrMatrix out;
  out.cols = rows.cols;
  (void)AverageRange(threads, &rows, nullptr, back, 0, rows.rows,
                     [&](std::vector<RowBlock>& blocks) {
                       size_t nnz = 0;
                       for (const RowBlock& block : blocks) nnz += block.col.size();
                       out.Reserve(rows.rows, nnz);
                       for (RowBlock& block : blocks) {
                         out.Append(block);
                         block = RowBlock{};
                       }
                       return absl::OkStatus();
                     });
  rows = std::move(out);
}

absl::Status ReciprocalPairs::Average(int threads, const RowStore& rows, uint64_t working_bytes,
                                      RowStore& out) const {
  std::vector<uint32_t> own, back;
  if (absl::Status s = Count(nullptr, &rows, own, back); !s.ok()) return s;
  const Emit append = [&](std::vector<RowBlock>& blocks) {
    for (RowBlock& block : blocks) {
      if (absl::Status s = out.Append(std::move(block)); !s.ok()) return s;
    }
    return absl::OkStatus();
  };
  const uint32_t n = rows.rows();
  for (uint32_t first = 0; first < n;) {
    uint32_t last = first + 1;
    uint64_t bytes = RangeBytes(own[first], back[first]);
    while (last < n && bytes + RangeBytes(own[last], back[last]) <= working_bytes) {
      bytes += RangeBytes(own[last], back[last]);
      ++last;
    }
    if (absl::Status s = AverageRange(threads, nullptr, &rows, back, first, last, append);
        !s.ok()) {
      return s;
    }
    first = last;
  }
  return out.Finish();
}

}  // namespace radflux
