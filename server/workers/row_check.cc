#include "server/workers/row_check.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

absl::Status BadRow(uint32_t row, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat("row ", row, ": ", what));
}

// The entries [begin, end) of `row`: columns ascending and in range, values finite, >= 0.
// Their sum in *sum.
absl::Status CheckEntries(const RowBlock& block, uint32_t row, uint64_t begin, uint64_t end,
                          uint32_t patch_count, double* sum) {
  *sum = 0;
  for (uint64_t k = begin; k < end; ++k) {
    const uint32_t c = block.col[k];
    if (c >= patch_count) {
      return BadRow(row, absl::StrCat("column ", c, " >= ", patch_count, " patches"));
    }
    if (k > begin && c <= block.col[k - 1]) {
      return BadRow(row, absl::StrCat("columns not strictly increasing (", block.col[k - 1],
                                      " then ", c, ")"));
    }
    const float v = block.value[k];
    if (!std::isfinite(v) || v < 0) {
      return BadRow(row, absl::StrCat("form factor F(", row, ",", c, ") = ", v,
                                      " is not a finite value >= 0"));
    }
    *sum += v;
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<std::vector<uint32_t>> CheckRowBlock(
    const RowBlock& block, uint32_t first_row, uint32_t row_count, uint32_t patch_count,
    const std::function<double(uint32_t row)>& max_row_sum) {
  if (block.row_begin.empty() || block.first_row != first_row || block.RowCount() != row_count) {
    return absl::InvalidArgumentError(absl::StrCat(
        "wrong rows (", block.row_begin.empty() ? 0 : block.RowCount(), " rows from ",
        block.first_row, ", leased ", row_count, " from ", first_row, ")"));
  }
  if (block.col.size() != block.value.size() || block.row_begin.front() != 0 ||
      block.row_begin.back() != block.col.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat("row offsets do not span the ", block.col.size(), " entries from 0"));
  }
  std::vector<uint32_t> high_sum;
  for (uint32_t i = 0; i < row_count; ++i) {
    const uint64_t begin = block.row_begin[i];
    const uint64_t end = block.row_begin[i + 1];
    const uint32_t row = first_row + i;
    if (end < begin) {
      return BadRow(row, absl::StrCat("offsets go backwards (", begin, " then ", end, ")"));
    }
    if (end > block.col.size()) {  // a later offset going back to the end hides this one
      return BadRow(row, absl::StrCat("offset ", end, " beyond the ", block.col.size(),
                                      " entries"));
    }
    double sum = 0;
    if (absl::Status s = CheckEntries(block, row, begin, end, patch_count, &sum); !s.ok()) return s;
    const double limit = max_row_sum ? max_row_sum(row) : 1.0;
    if (sum > limit + kRowSumTolerance) high_sum.push_back(row);
  }
  return high_sum;
}

std::vector<uint32_t> SampleRows(uint32_t first, uint32_t count, double fraction,
                                 std::mt19937_64& rng) {
  if (!(fraction > 0) || count == 0) return {};
  const double wanted = std::round(std::min(1.0, fraction) * count);
  const uint32_t k = std::max<uint32_t>(1, static_cast<uint32_t>(wanted));
  std::vector<uint32_t> all(count);
  for (uint32_t i = 0; i < count; ++i) all[i] = first + i;
  std::vector<uint32_t> picked;
  std::sample(all.begin(), all.end(), std::back_inserter(picked), k, rng);
  return picked;  // std::sample keeps the input's order: ascending
}

absl::Status VerifyRows(const RowBlock& block, const std::vector<uint32_t>& rows,
                        const RowRebuilder& rebuild) {
  for (uint32_t row : rows) {
    const RowBlock own = rebuild(row, 1);
    const std::span<const uint32_t> cols = block.View().RowCols(row);
    const std::span<const float> values = block.View().RowValues(row);
    const bool same =
        own.col.size() == cols.size() &&
        std::equal(cols.begin(), cols.end(), own.col.begin()) &&
        (values.empty() ||
         std::memcmp(values.data(), own.value.data(), values.size() * sizeof(float)) == 0);
    if (!same) {
      return BadRow(row, absl::StrCat("differs from the server's own (", cols.size(), " vs ",
                                      own.col.size(), " entries)"));
    }
  }
  return absl::OkStatus();
}

absl::Status CheckDenseBlock(const StoredRowBlock& block, uint32_t first_row, uint32_t row_count,
                             const DenseRows& dense, const std::vector<uint32_t>& sample) {
  if (!block.view_factors || block.block.first_row != first_row ||
      block.block.RowCount() != row_count) {
    return absl::InvalidArgumentError(absl::StrCat("not the view-factor rows ", first_row, "+",
                                                   row_count, " leased"));
  }
  if (block.values.size() != dense.values(first_row, row_count)) {
    return absl::InvalidArgumentError(absl::StrCat(block.values.size(), " values for rows ",
                                                   first_row, "+", row_count, ", not ",
                                                   dense.values(first_row, row_count)));
  }
  for (size_t k = 0; k < block.values.size(); ++k) {
    if (!(std::isfinite(block.values[k]) && block.values[k] >= 0)) {
      return absl::InvalidArgumentError(absl::StrCat("value ", k, " is ", block.values[k]));
    }
  }
  for (uint32_t row : sample) {
    const std::vector<double> own = dense.rebuild(row);
    const size_t at = dense.values(first_row, row - first_row);
    if (own.size() > block.values.size() - at ||
        std::memcmp(own.data(), block.values.data() + at, own.size() * sizeof(double)) != 0) {
      return absl::InvalidArgumentError(
          absl::StrCat("view-factor row ", row, " differs from the server's own"));
    }
  }
  return absl::OkStatus();
}

}  // namespace radflux
