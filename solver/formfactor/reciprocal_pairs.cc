#include "solver/formfactor/reciprocal_pairs.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <utility>

#include "solver/core/parallel.h"
#include "solver/sparse/entry_buckets.h"

namespace radflux {
namespace {

constexpr uint32_t kRowsPerTask = 256;
constexpr uint32_t kNoColumn = std::numeric_limits<uint32_t>::max();
// A bucket's buffer holds at least this many back hits (4 KiB) before it is written.
constexpr size_t kLeastBucketBuffer = 4096 / sizeof(BucketEntry);

// Another row's hit on row i: (j, h_ji = k_j F_ji).
using BackHit = std::pair<uint32_t, float>;

// Bytes a row takes in a range being averaged: its own entries and back hits, and offsets.
uint64_t RangeBytes(uint32_t own, uint32_t back) {
  return uint64_t{own} * (sizeof(uint32_t) + sizeof(float)) + uint64_t{back} * sizeof(BackHit) +
         2 * sizeof(uint64_t);
}

// Appends row i of `rows` to `block`.
void CopyRow(const RowsView& rows, uint32_t i, RowBlock& block) {
  const auto cols = rows.RowCols(i);
  const auto vals = rows.RowValues(i);
  block.col.insert(block.col.end(), cols.begin(), cols.end());
  block.value.insert(block.value.end(), vals.begin(), vals.end());
  block.EndRow();
}

}  // namespace

// The back hits on rows [first, last), each row's ascending in j when they are put in
// ascending j (as a pass over the rows in order meets them).
class ReciprocalPairs::RangeHits {
 public:
  RangeHits(std::span<const uint32_t> back, uint32_t first_row, uint32_t last_row)
      : first(first_row), last(last_row), begin_(last_row - first_row + 1, 0) {
    for (uint32_t r = 0; r < last - first; ++r) begin_[r + 1] = begin_[r] + back[first + r];
    hits_.resize(begin_.back());
    next_.assign(begin_.begin(), begin_.end() - 1);
  }
  void Put(uint32_t i, uint32_t j, float h) { hits_[next_[i - first]++] = {j, h}; }
  std::span<const BackHit> Of(uint32_t i) const {
    return {hits_.data() + begin_[i - first], hits_.data() + begin_[i - first + 1]};
  }

  const uint32_t first, last;

 private:
  std::vector<uint64_t> begin_, next_;
  std::vector<BackHit> hits_;
};

ReciprocalPairs::ReciprocalPairs(const RowContext& context, int rays,
                                 std::span<const uint8_t> cosine) {
  const size_t n = context.opaque_area.size();
  area_ = context.opaque_area;
  rays_.resize(n);
  density_.resize(n);
  takes_part_.assign(n, 0);
  exposure_.resize(n);
  for (size_t u = 0; u < n; ++u) {
    exposure_[u] = context.Exposure(static_cast<uint32_t>(u));
    rays_[u] = context.RowRays(static_cast<uint32_t>(u), rays);
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

void ReciprocalPairs::Gather(const RowsView& rows, RangeHits& hits) const {
  for (uint32_t j = rows.first_row; j < rows.EndRow(); ++j) {
    if (!takes_part_[j]) continue;
    const auto cols = rows.RowCols(j);
    const auto vals = rows.RowValues(j);
    for (size_t e = std::lower_bound(cols.begin(), cols.end(), hits.first) - cols.begin();
         e < cols.size() && cols[e] < hits.last; ++e) {
      const uint32_t i = cols[e];
      if (i != j && takes_part_[i]) hits.Put(i, j, static_cast<float>(Hits(j, vals[e])));
    }
  }
}

std::vector<RowBlock> ReciprocalPairs::AverageRows(int threads, const RowsView& own,
                                                   const RangeHits& hits) const {
  const uint32_t count = hits.last - hits.first;
  const int64_t task_count = (count + kRowsPerTask - 1) / kRowsPerTask;
  std::vector<RowBlock> blocks(static_cast<size_t>(task_count));
  ParallelFor(task_count, 1, threads, [&](int64_t begin_task, int64_t end_task) {
    std::vector<std::pair<size_t, double>> averaged;  // a row's averaged entries: where, value
    for (int64_t t = begin_task; t < end_task; ++t) {
      RowBlock& block = blocks[static_cast<size_t>(t)];
      block.first_row = hits.first + static_cast<uint32_t>(t) * kRowsPerTask;
      const uint32_t end = std::min(hits.last, block.first_row + kRowsPerTask);
      size_t entries = 0;
      for (uint32_t i = block.first_row; i < end; ++i) {
        entries += own.RowCols(i).size() + hits.Of(i).size();
      }
      block.col.reserve(entries);
      block.value.reserve(entries);
      block.row_begin.reserve(end - block.first_row + 1);
      for (uint32_t i = block.first_row; i < end; ++i) {
        if (!takes_part_[i]) {  // no pair: no back hits either
          CopyRow(own, i, block);
          continue;
        }
        const auto cols = own.RowCols(i);
        const auto vals = own.RowValues(i);
        const std::span<const BackHit> back = hits.Of(i);
        const double a_i = area_[i], d_i = density_[i];
        averaged.clear();
        double own_sum = 0, averaged_sum = 0;
        size_t a = 0, h = 0;
        while (a < cols.size() || h < back.size()) {
          const uint32_t own_col = a < cols.size() ? cols[a] : kNoColumn;
          const uint32_t back_col = h < back.size() ? back[h].first : kNoColumn;
          const uint32_t j = std::min(own_col, back_col);
          const float own_value = own_col == j ? vals[a++] : 0.0f;
          if (!takes_part_[j] || j == i) {  // as built (back hits come in pairs only)
            block.Add(j, own_value);
            continue;
          }
          const double back_value = back_col == j ? back[h++].second : 0.0;
          const double v = (Hits(i, own_value) + back_value) / (a_i * (d_i + density_[j]));
          own_sum += own_value;
          averaged_sum += v;
          averaged.emplace_back(block.col.size(), v);
          block.Add(j, 0);
        }
        // Scaled back to the sum of the row's own rays; none left when those met no pair.
        const double scale = averaged_sum > 0 ? own_sum / averaged_sum : 0;
        if (scale > 0) {
          for (const auto& [at, v] : averaged) block.value[at] = static_cast<float>(v * scale);
        } else if (!averaged.empty()) {
          size_t kept = block.row_begin.back();
          for (size_t e = kept; e < block.col.size(); ++e) {
            if (block.value[e] > 0) {
              block.col[kept] = block.col[e];
              block.value[kept++] = block.value[e];
            }
          }
          block.col.resize(kept);
          block.value.resize(kept);
        }
        block.EndRow();
      }
    }
  });
  return blocks;
}

void ReciprocalPairs::Average(int threads, CsrMatrix& rows) const {
  std::vector<uint32_t> own, back;
  (void)Count(&rows, nullptr, own, back);  // rows in memory: nothing to fail
  RangeHits hits(back, 0, rows.rows);
  Gather(rows.View(), hits);
  std::vector<RowBlock> blocks = AverageRows(threads, rows.View(), hits);
  CsrMatrix out;
  out.cols = rows.cols;
  size_t nnz = 0;
  for (const RowBlock& block : blocks) nnz += block.col.size();
  out.Reserve(rows.rows, nnz);
  for (RowBlock& block : blocks) {
    out.Append(block);
    block = RowBlock{};
  }
  rows = std::move(out);
}

absl::StatusOr<SpilledAveraging> ReciprocalPairs::Average(int threads, const RowStore& rows,
                                                          uint64_t working_bytes,
                                                          const std::string& directory,
                                                          RowStore& out) const {
  std::vector<uint32_t> own, back;
  if (absl::Status s = Count(nullptr, &rows, own, back); !s.ok()) return s;
  const uint32_t n = rows.rows();
  std::vector<uint32_t> bounds = {0};  // range r is rows [bounds[r], bounds[r + 1])
  for (uint32_t first = 0; first < n;) {
    uint32_t last = first + 1;
    uint64_t bytes = RangeBytes(own[first], back[first]);
    while (last < n && bytes + RangeBytes(own[last], back[last]) <= working_bytes) {
      bytes += RangeBytes(own[last], back[last]);
      ++last;
    }
    bounds.push_back(last);
    first = last;
  }
  SpilledAveraging result;
  result.ranges = static_cast<int>(bounds.size()) - 1;

  // Each back hit to its range's bucket (more than one range), in ascending j.
  std::optional<EntryBuckets> buckets;
  absl::Status failed;
  if (result.ranges > 1) {
    const size_t buffer =
        std::max<size_t>(kLeastBucketBuffer,
                         working_bytes / sizeof(BucketEntry) / static_cast<size_t>(result.ranges));
    buckets.emplace(directory, static_cast<size_t>(result.ranges), buffer);
    absl::Status read = rows.ForEach([&](const RowsView& view) {
      for (uint32_t j = view.first_row; j < view.EndRow() && failed.ok(); ++j) {
        if (!takes_part_[j]) continue;
        const auto cols = view.RowCols(j);
        const auto vals = view.RowValues(j);
        size_t r = 0;
        for (size_t e = 0; e < cols.size() && failed.ok(); ++e) {
          const uint32_t i = cols[e];
          if (i == j || !takes_part_[i]) continue;
          while (i >= bounds[r + 1]) ++r;  // columns ascend
          failed = buckets->Add(r, {i, j, static_cast<float>(Hits(j, vals[e]))});
        }
      }
    });
    if (!read.ok()) return read;
    if (failed.ok()) failed = buckets->Finish();
    if (!failed.ok()) return failed;
  }

  // Each range's own rows copied as the pass meets them, averaged at the range's end.
  std::optional<RangeHits> only;  // one range: its hits, gathered in this same pass
  if (result.ranges == 1) only.emplace(back, 0, n);
  RowBlock own_rows;
  size_t r = 0;
  absl::Status read = rows.ForEach([&](const RowsView& view) {
    if (only) Gather(view, *only);
    for (uint32_t j = view.first_row; j < view.EndRow() && failed.ok(); ++j) {
      CopyRow(view, j, own_rows);
      if (j + 1 < bounds[r + 1]) continue;
      std::optional<RangeHits> range;
      if (!only) {
        range.emplace(back, bounds[r], bounds[r + 1]);
        failed = buckets->Read(r, [&](std::span<const BucketEntry> entries) {
          for (const BucketEntry& e : entries) range->Put(e.row, e.col, e.value);
        });
        if (!failed.ok()) return;
      }
      for (RowBlock& block : AverageRows(threads, own_rows.View(), only ? *only : *range)) {
        if (failed = out.Append(std::move(block)); !failed.ok()) return;
      }
      own_rows = RowBlock{};
      own_rows.first_row = j + 1;
      ++r;
    }
  });
  if (!read.ok()) return read;
  if (!failed.ok()) return failed;
  if (buckets) {
    result.bucket_bytes_written = buckets->BytesWritten();
    result.bucket_bytes_read = buckets->BytesRead();
  }
  if (absl::Status s = out.Finish(); !s.ok()) return s;
  return result;
}

}  // namespace radflux
