// RowStore: form-factor rows that may not fit in memory. Row blocks arrive in row order;
// they are gathered into chunks of about kRowChunkBytes, kept in memory while the bytes
// held stay within a budget and handed to a BlockSpill beyond it. ForEach streams every
// row back in order, reading spilled chunks ahead on a background thread so that reading
// overlaps the caller's work on the previous chunk. Exactly the rows appended come back.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "absl/status/status.h"
#include "solver/sparse/block_spill.h"
#include "solver/sparse/csr_matrix.h"

namespace radflux {

// Target size of one chunk: the unit of spilling, reading and of one streamed range.
inline constexpr uint64_t kRowChunkBytes = 8ull << 20;
// Spilled chunks read ahead of the one being used.
inline constexpr int kRowReadAhead = 2;

using RowsFn = std::function<void(const RowsView&)>;

// What ForEach has read from the spill since the store was made.
struct RowReadStats {
  int passes = 0;           // ForEach calls that read spilled chunks
  uint64_t bytes = 0;       // bytes read back
  double read_seconds = 0;  // reader thread time inside BlockSpill::Read
  double wait_seconds = 0;  // caller time blocked waiting for a chunk (not overlapped)
};

class RowStore {
 public:
  // n x `cols` rows; up to `memory_budget` bytes of rows stay in memory, the rest go to
  // `spill` (may be null when nothing is to spill: then a chunk over budget is an error).
  // A chunk is sealed once it holds `chunk_bytes` or more.
  RowStore(uint32_t cols, uint64_t memory_budget, std::unique_ptr<BlockSpill> spill,
           uint64_t chunk_bytes = kRowChunkBytes);

  // Appends the next block (its first_row must be rows()). INVALID_ARGUMENT for a block out
  // of order or a column >= cols; the spill's error when writing fails.
  absl::Status Append(RowBlock block);
  // Seals the last partial chunk; call once after the last Append and before ForEach.
  absl::Status Finish();

  // Calls fn on consecutive ranges covering all rows in order (one chunk each). Returns
  // the spill's read error, if any (fn has then seen only a prefix of the rows). One
  // ForEach at a time.
  absl::Status ForEach(const RowsFn& fn) const;

  uint32_t rows() const { return rows_; }
  uint32_t cols() const { return cols_; }
  uint64_t nnz() const { return nnz_; }
  uint64_t budget() const { return budget_; }            // bytes of rows kept in memory at most
  uint64_t chunk_bytes() const { return chunk_bytes_; }  // a chunk is sealed at this size
  // All rows, CSR layout per chunk (one row offset more per chunk than one CsrMatrix).
  uint64_t Bytes() const { return memory_bytes_ + spilled_bytes_; }
  uint64_t MemoryBytes() const { return memory_bytes_; }    // rows held in memory
  uint64_t SpilledBytes() const { return spilled_bytes_; }  // rows in the spill
  const RowReadStats& read_stats() const { return read_stats_; }

 private:
  struct Chunk {
    RowBlock rows;             // empty when spilled
    int64_t spill_index = -1;  // >= 0: in the spill
  };
  absl::Status Seal();
  absl::Status StreamWithReadAhead(const RowsFn& fn) const;

  uint32_t cols_;
  uint64_t budget_;
  uint64_t chunk_bytes_;
  std::unique_ptr<BlockSpill> spill_;
  uint32_t rows_ = 0;
  uint64_t nnz_ = 0, memory_bytes_ = 0, spilled_bytes_ = 0;
  size_t spilled_chunks_ = 0;
  std::vector<Chunk> chunks_;
  RowBlock open_;  // the chunk being filled
  mutable RowReadStats read_stats_;
  // The read-ahead buffers, kept across passes: a pass allocates nothing once the first
  // has sized them (fresh buffers per pass, filled on a fresh reader thread, each landed
  // in a new malloc arena and the server's RSS grew by the spilled bytes pass after pass).
  mutable std::array<RowBlock, kRowReadAhead> read_buffers_;
};

// The rows of a system, in memory (`matrix`) or in a store: calls fn on consecutive
// ranges in row order. Exactly one of the two must be non-null.
absl::Status ForEachRows(const CsrMatrix* matrix, const RowStore* store, const RowsFn& fn);

}  // namespace radflux
