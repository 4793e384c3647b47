// The checks of a row block that came from a worker, which the server does not trust:
// its structure and values (all of them), then a sample of its rows recomputed here. The
// rows are bit-identical for any partition into blocks, so a recomputed row equals an
// honest worker's exactly; any difference is a lie (or a broken worker) and is caught.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "absl/status/statusor.h"
#include "server/store/stored_codec.h"
#include "solver/sparse/csr_matrix.h"

namespace radflux {

// How far above 1 a row's sum of form factors may be before the row is recomputed here
// (coincident or overlapping faces can sum above 1 honestly: such rows are checked, not
// refused).
inline constexpr double kRowSumTolerance = 1e-3;

// Rows [first, first + count) built on the server, as a worker would build them.
using RowRebuilder = std::function<RowBlock(uint32_t first, uint32_t count)>;

// INVALID_ARGUMENT naming the row and what is wrong unless `block` has exactly the leased
// rows (`first_row`, `row_count`), offsets from 0 that never go backwards nor beyond the
// entries and end at the entry count, columns strictly increasing and < `patch_count` in
// every row, and every value finite and >= 0. On success, the rows whose sum exceeds
// max_row_sum(row) (1 when not given) + kRowSumTolerance (absolute row numbers): they must
// be recomputed before the block is trusted.
absl::StatusOr<std::vector<uint32_t>> CheckRowBlock(
    const RowBlock& block, uint32_t first_row, uint32_t row_count, uint32_t patch_count,
    const std::function<double(uint32_t row)>& max_row_sum = {});

// The rows of a block of `count` rows from `first` to recompute: `fraction` of them rounded,
// at least one when fraction > 0, none when it is 0; distinct, ascending, drawn with `rng`.
std::vector<uint32_t> SampleRows(uint32_t first, uint32_t count, double fraction,
                                 std::mt19937_64& rng);

// INVALID_ARGUMENT naming the first row that differs unless every row of `rows` (absolute
// row numbers inside `block`) equals the server's own (`rebuild`) bit for bit.
absl::Status VerifyRows(const RowBlock& block, const std::vector<uint32_t>& rows,
                        const RowRebuilder& rebuild);

// A view-factor job's rows (SurfaceRowPlan): the values a block of rows holds (`values(first,
// count)`; row r of a block from `first` starts at values(first, r - first)), and the
// server's own values of one row.
struct DenseRows {
  std::function<size_t(uint32_t first, uint32_t count)> values;
  std::function<std::vector<double>(uint32_t row)> rebuild;
};

// INVALID_ARGUMENT naming what is wrong unless `block` is a view-factor block with exactly
// the leased rows, as many values as they hold, every value finite and >= 0, and each row
// of `sample` (absolute row numbers) equal to the server's own (dense.rebuild) bit for bit.
absl::Status CheckDenseBlock(const StoredRowBlock& block, uint32_t first_row, uint32_t row_count,
                             const DenseRows& dense, const std::vector<uint32_t>& sample);

}  // namespace radflux
