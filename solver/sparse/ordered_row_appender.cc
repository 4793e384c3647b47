#include "solver/sparse/ordered_row_appender.h"

#include "absl/strings/str_cat.h"

namespace radflux {

absl::Status OrderedRowAppender::Put(uint32_t index, RowBlock block) {
  {
    std::lock_guard lock(pending_mutex_);
    if (!error_.ok()) return error_;
    pending_.emplace(index, std::move(block));
  }
  return Drain();
}

// A block left behind by a drainer that was just finishing goes with the next Put, or with
// the drain in Finish.
absl::Status OrderedRowAppender::Drain() {
  std::unique_lock drainer(drain_mutex_, std::try_to_lock);
  if (!drainer.owns_lock()) return absl::OkStatus();
  for (;;) {
    RowBlock block;
    {
      std::lock_guard lock(pending_mutex_);
      const auto it = pending_.find(next_);
      if (it == pending_.end()) return error_;
      block = std::move(it->second);
      pending_.erase(it);
      ++next_;
    }
    if (absl::Status s = store_.Append(std::move(block)); !s.ok()) {
      std::lock_guard lock(pending_mutex_);
      error_ = s;
      return s;
    }
  }
}

absl::Status OrderedRowAppender::Finish() {
  if (absl::Status s = Drain(); !s.ok()) return s;
  {
    std::lock_guard lock(pending_mutex_);
    if (!pending_.empty()) {
      return absl::InternalError(absl::StrCat("row block ", next_, " never came"));
    }
  }
  return store_.Finish();
}

}  // namespace radflux
