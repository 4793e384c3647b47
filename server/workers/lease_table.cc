#include "server/workers/lease_table.h"

namespace radflux {

LeaseTable::LeaseTable(const std::vector<uint32_t>& blocks) {
  for (uint32_t b : blocks) {
    if (states_.emplace(b, Entry{}).second) pending_.push_back(b);
  }
}

std::optional<uint32_t> LeaseTable::Take(uint64_t worker, Clock::time_point deadline) {
  for (auto it = pending_.begin(); it != pending_.end(); ++it) {
    Entry& e = states_.at(*it);
    if (e.state != State::kPending) continue;  // stale queue entry: skipped below
    if (e.local_only && worker != kLocal) continue;
    const uint32_t block = *it;
    pending_.erase(it);
    e.state = State::kLeased;
    e.holder = worker;
    e.deadline = deadline;
    e.leased_at = Clock::now();
    return block;
  }
  // Drop stale entries so the queue does not grow.
  std::erase_if(pending_, [&](uint32_t b) { return states_.at(b).state != State::kPending; });
  return std::nullopt;
}

bool LeaseTable::Claim(uint32_t block) {
  const auto it = states_.find(block);
  if (it == states_.end() || it->second.state == State::kClaimed ||
      it->second.state == State::kDone) {
    return false;
  }
  it->second.state = State::kClaimed;
  return true;
}

void LeaseTable::Finish(uint32_t block) {
  Entry& e = states_.at(block);
  if (e.state == State::kDone) return;
  e.state = State::kDone;
  ++done_;
}

void LeaseTable::MakeLocalOnly(uint32_t block) {
  const auto it = states_.find(block);
  if (it == states_.end()) return;
  it->second.local_only = true;
  if (it->second.state == State::kLeased) Requeue(block);
}

void LeaseTable::Requeue(uint32_t block) {
  Entry& e = states_.at(block);
  e.state = State::kPending;
  e.holder = 0;
  pending_.push_front(block);  // a lost block goes first: it holds the job back
}

std::vector<uint32_t> LeaseTable::Release(uint64_t worker) {
  std::vector<uint32_t> released;
  for (auto& [block, e] : states_) {
    if (e.state == State::kLeased && e.holder == worker) released.push_back(block);
  }
  for (uint32_t b : released) Requeue(b);
  return released;
}

std::vector<uint32_t> LeaseTable::Expire(Clock::time_point now) {
  std::vector<uint32_t> expired;
  for (auto& [block, e] : states_) {
    if (e.state == State::kLeased && e.holder != kLocal && e.deadline <= now) {
      expired.push_back(block);
    }
  }
  for (uint32_t b : expired) Requeue(b);
  return expired;
}

std::optional<LeaseTable::Backup> LeaseTable::TakeBackup(Clock::time_point leased_before) {
  std::optional<Backup> oldest;
  for (const auto& [block, e] : states_) {
    if (e.state != State::kLeased || e.holder == kLocal || e.leased_at > leased_before) continue;
    if (!oldest || e.leased_at < oldest->leased_at) oldest = Backup{block, e.holder, e.leased_at};
  }
  if (oldest) states_.at(oldest->block).holder = kLocal;
  return oldest;
}

std::optional<uint64_t> LeaseTable::Holder(uint32_t block) const {
  const auto it = states_.find(block);
  if (it == states_.end() || it->second.state != State::kLeased) return std::nullopt;
  return it->second.holder;
}

}  // namespace radflux
