#include "server/store/row_sink.h"

namespace radflux {

RowSink::RowSink(uint32_t n, uint32_t block_count, std::unique_ptr<RowStore> store)
    : n_(n), store_(std::move(store)), has_(block_count), stats_(block_count) {
  if (store_) {
    appender_.emplace(*store_);
  } else {
    blocks_.resize(block_count);
  }
}

absl::Status RowSink::Put(uint32_t index, std::shared_ptr<const StoredRowBlock> block) {
  {
    std::lock_guard lock(mu_);
    if (has_[index]) return absl::OkStatus();
    has_[index] = true;
    stats_[index] = block->stats;
    if (!store_) {
      blocks_[index] = std::move(block);
      return absl::OkStatus();
    }
  }
  return appender_->Put(index, block->block);  // a copy: the row block writer may hold it
}

bool RowSink::Has(uint32_t index) const {
  std::lock_guard lock(mu_);
  return has_[index];
}

absl::StatusOr<JobRows> RowSink::Finish() {
  JobRows rows;
  for (const RowBlockStats& s : stats_) rows.stats.Merge(s);
  if (store_) {
    if (absl::Status s = appender_->Finish(); !s.ok()) return s;
    rows.store = std::move(store_);
    return rows;
  }
  rows.matrix.cols = n_;
  size_t nnz = 0;
  for (const auto& b : blocks_) nnz += b->block.col.size();
  rows.matrix.Reserve(n_, nnz);
  for (auto& b : blocks_) {
    rows.matrix.Append(b->block);
    b.reset();  // the writer may still hold it until its checkpoint
  }
  return rows;
}

}  // namespace radflux
