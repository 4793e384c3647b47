// The checks of a worker's row block (row_check.h) against blocks the service fuzzer
// (tests/fuzz/service_request_fuzzer.cc) built: a middle row offset beyond the entries,
// hidden by a later offset going back to the end, made CheckRowBlock read past the block's
// columns (a heap overflow a worker with the token could send); an empty vector decoded
// with a null pointer passed to memcpy.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace radflux
