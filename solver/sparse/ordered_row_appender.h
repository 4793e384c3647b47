// OrderedRowAppender: takes row blocks that finish in any order on any thread and appends
// them to a RowStore in row order. Blocks wait until they are next; one thread at a time
// appends (the store may write to disk) while the others leave their block and go on.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>

#include "absl/status/status.h"
#include "solver/sparse/row_store.h"

namespace radflux {

class OrderedRowAppender {
 public:
  explicit OrderedRowAppender(RowStore& store) : store_(store) {}

  // Block number `index` (0, 1, ... in row order), each exactly once. Thread-safe. Returns
  // the store's error, once it has failed, to every later call.
  absl::Status Put(uint32_t index, RowBlock block);
  // Appends what is left and finishes the store; INTERNAL when a block never came.
  absl::Status Finish();

 private:
  absl::Status Drain();

  RowStore& store_;
  std::mutex pending_mutex_;  // guards pending_, next_, error_
  std::mutex drain_mutex_;    // held by the one thread appending
  std::map<uint32_t, RowBlock> pending_;
  uint32_t next_ = 0;
  absl::Status error_;
};

}  // namespace radflux
