// RowSink: where a server job's row blocks go as they become available, stored ones read
// back and built ones, in any order and from any thread: kept until the last one and
// assembled into one CsrMatrix, or (when the job spills) appended in row order to a
// RowStore as soon as they are next, the sink keeping no reference to an appended block.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "server/store/stored_codec.h"
#include "solver/sparse/ordered_row_appender.h"
#include "solver/sparse/row_store.h"

namespace radflux {

// A job's rows, in memory (matrix) or in a store (then matrix is empty).
struct JobRows {
  CsrMatrix matrix;
  std::unique_ptr<RowStore> store;
  RowBlockStats stats;  // merged in row order either way
  double seconds = 0;
};

class RowSink {
 public:
  // `block_count` blocks of `n` columns; `store` null: rows in memory.
  RowSink(uint32_t n, uint32_t block_count, std::unique_ptr<RowStore> store);

  // Thread-safe. A block number already put is ignored. Returns the store's error.
  absl::Status Put(uint32_t index, std::shared_ptr<const StoredRowBlock> block);
  bool Has(uint32_t index) const;
  // After every block was put: the rows and their statistics.
  absl::StatusOr<JobRows> Finish();

 private:
  const uint32_t n_;
  std::unique_ptr<RowStore> store_;
  std::optional<OrderedRowAppender> appender_;  // with a store
  mutable std::mutex mu_;                       // guards has_, blocks_, stats_
  std::vector<bool> has_;
  std::vector<std::shared_ptr<const StoredRowBlock>> blocks_;  // without a store
  std::vector<RowBlockStats> stats_;
};

}  // namespace radflux
