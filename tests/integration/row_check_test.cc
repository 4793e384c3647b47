// The checks of a worker's row block (row_check.h) against blocks the service fuzzer
// (tests/fuzz/service_request_fuzzer.cc) built: a middle row offset beyond the entries,
// hidden by a later offset going back to the end, made CheckRowBlock read past the block's
// columns (a heap overflow a worker with the token could send); an empty vector decoded
// with a null pointer passed to memcpy.
#include <gtest/gtest.h>

#include <cmath>

#include "server/store/stored_codec.h"
#include "server/workers/row_check.h"

namespace radflux {
namespace {

TEST(RowCheck, OffsetBeyondTheEntriesIsRefusedBeforeAnyEntryIsRead) {
  RowBlock block;
  block.first_row = 4;
  block.row_begin = {0, 1000000, 2};  // row 4 claims a million entries, row 5 goes back
  block.col = {0, 1};
  block.value = {0.1f, 0.2f};
  const absl::StatusOr<std::vector<uint32_t>> checked = CheckRowBlock(block, 4, 2, 64);
  EXPECT_EQ(checked.status().code(), absl::StatusCode::kInvalidArgument) << checked.status();
  EXPECT_NE(checked.status().message().find("row 4: offset 1000000 beyond the 2 entries"),
            std::string::npos)
      << checked.status();
}

TEST(RowCheck, WellFormedBlockPassesAndRowsAboveOneAreNamed) {
  RowBlock block;
  block.first_row = 4;
  block.row_begin = {0, 2, 3};
  block.col = {0, 5, 63};
  block.value = {0.6f, 0.6f, 0.5f};  // row 4 sums to 1.2: to recompute
  const absl::StatusOr<std::vector<uint32_t>> checked = CheckRowBlock(block, 4, 2, 64);
  ASSERT_TRUE(checked.ok()) << checked.status();
  EXPECT_EQ(*checked, std::vector<uint32_t>{4});
}

// A row may honestly sum up to its own limit (RowContext::MaxRowSum: 1 / rho below rho =
// 0.999, so that sampled rows of closed rooms keep their noise unbiased): only rows above
// that limit are recomputed.
TEST(RowCheck, RowsAreNamedAboveTheirOwnLimit) {
  RowBlock block;
  block.first_row = 4;
  block.row_begin = {0, 2, 3};
  block.col = {0, 5, 63};
  block.value = {0.6f, 0.6f, 0.5f};  // row 4 sums to 1.2
  const auto limit = [](double rho) {
    return [rho](uint32_t) { return 0.999 / rho; };
  };
  const absl::StatusOr<std::vector<uint32_t>> within = CheckRowBlock(block, 4, 2, 64, limit(0.8));
  ASSERT_TRUE(within.ok()) << within.status();
  EXPECT_TRUE(within->empty());  // limit 1.249
  const absl::StatusOr<std::vector<uint32_t>> above = CheckRowBlock(block, 4, 2, 64, limit(0.9));
  ASSERT_TRUE(above.ok()) << above.status();
  EXPECT_EQ(*above, std::vector<uint32_t>{4});  // limit 1.11
}

TEST(RowCheck, EmptyRowBlockRoundTripsThroughItsEncoding) {
  StoredRowBlock empty;
  empty.block.first_row = 7;
  empty.block.EndRow();  // one row, no entries: col and value stay empty
  const absl::StatusOr<StoredRowBlock> decoded = DecodeRowBlock(EncodeRowBlock(empty));
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_EQ(decoded->block.first_row, 7u);
  EXPECT_EQ(decoded->block.RowCount(), 1u);
  EXPECT_TRUE(decoded->block.col.empty());
  EXPECT_TRUE(CheckRowBlock(decoded->block, 7, 1, 64).ok());
}

// A view-factor block (issue 23, CheckDenseBlock): rows of widths 3, 2, 1 (a pair triangle's);
// the honest block passes, its encoding round-trips bit for bit, and a block with a wrong
// value count, a negative or NaN value, or one bit changed in a sampled row is refused.
TEST(RowCheck, ViewFactorBlockIsCheckedValueByValueAndSampledRowsBitForBit) {
  const std::vector<double> values = {0.1, 0.2, 0.3, 0.25, 0.125, 1.0 / 3};
  const DenseRows dense{
      [](uint32_t first, uint32_t count) {  // widths 3, 2, 1 from row 0
        size_t n = 0;
        for (uint32_t r = first; r < first + count; ++r) n += 3 - r;
        return n;
      },
      [&](uint32_t row) {
        const size_t at[] = {0, 3, 5};
        return std::vector<double>(values.begin() + at[row], values.begin() + at[row] + 3 - row);
      }};
  StoredRowBlock block;
  block.view_factors = true;
  block.block.first_row = 0;
  block.block.row_begin.assign(4, 0);
  block.values = values;
  const absl::StatusOr<StoredRowBlock> decoded = DecodeRowBlock(EncodeRowBlock(block));
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_TRUE(decoded->view_factors);
  EXPECT_EQ(decoded->values, values);
  EXPECT_TRUE(CheckDenseBlock(*decoded, 0, 3, dense, {0, 1, 2}).ok());
  EXPECT_FALSE(CheckDenseBlock(*decoded, 0, 2, dense, {}).ok()) << "another lease's rows";
  StoredRowBlock bad = block;
  bad.values.pop_back();
  EXPECT_FALSE(CheckDenseBlock(bad, 0, 3, dense, {}).ok()) << "a value missing";
  bad = block;
  bad.values[4] = -0.5;
  EXPECT_FALSE(CheckDenseBlock(bad, 0, 3, dense, {}).ok()) << "a negative value";
  bad.values[4] = std::nan("");
  EXPECT_FALSE(CheckDenseBlock(bad, 0, 3, dense, {}).ok()) << "NaN";
  bad = block;
  bad.values[4] = std::nextafter(values[4], 1.0);  // row 1, one bit off
  EXPECT_TRUE(CheckDenseBlock(bad, 0, 3, dense, {0, 2}).ok()) << "row 1 not sampled";
  const absl::Status lie = CheckDenseBlock(bad, 0, 3, dense, {1});
  EXPECT_EQ(lie.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(lie.message().find("view-factor row 1 differs from the server's own"),
            std::string::npos)
      << lie;
}

}  // namespace
}  // namespace radflux
