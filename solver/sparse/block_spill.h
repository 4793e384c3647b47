// BlockSpill: where a RowStore keeps the row blocks that do not fit its memory budget.
// Blocks are written once, in row order, and read back by index any number of times.
// FileBlockSpill writes one local file; a server could back it with the block files its
// job store already holds (Write then only records where block `index` lives).
#pragma once

#include <cstddef>
#include <cstdint>

#include "absl/status/status.h"
#include "solver/sparse/csr_matrix.h"

namespace radflux {

class BlockSpill {
 public:
  virtual ~BlockSpill() = default;
  // Stores `block` as the next index (0, 1, 2, ... in call order). Errors name the file
  // and what failed (cannot create, disk full).
  virtual absl::Status Write(const RowBlock& block) = 0;
  // Reads block `index` back into `out`, reusing its capacity. Called from one thread at a
  // time (a RowStore's reader), never concurrently with Write.
  virtual absl::Status Read(size_t index, RowBlock& out) const = 0;
  // Bytes the written blocks take where they are kept.
  virtual uint64_t BytesWritten() const = 0;
};

}  // namespace radflux
