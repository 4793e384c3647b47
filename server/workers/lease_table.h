// LeaseTable: the state of every row block still to build in one job's row phase: pending,
// leased to a worker until a deadline, built locally by a server thread (also as a backup of
// a remote lease), claimed (a result is being stored) or done. Each block is stored once: the first result claims it, later
// duplicates are refused. Not thread-safe (RowFarm guards it).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <vector>

namespace radflux {

class LeaseTable {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr uint64_t kLocal = 0;  // the "worker" id of the server's own threads

  // `blocks`: the indices of the blocks still to build, in the order to hand them out.
  explicit LeaseTable(const std::vector<uint32_t>& blocks);

  // The next pending block for worker `worker` (kLocal: a server thread, no deadline).
  // Blocks marked local-only are never given to a remote worker.
  std::optional<uint32_t> Take(uint64_t worker, Clock::time_point deadline);
  // The first result of a block claims it (true); a block already claimed or done is a
  // duplicate (false). A claimed block must be Finish()ed.
  bool Claim(uint32_t block);
  void Finish(uint32_t block);
  // A block whose remote result was too large for the wire: back to pending, local only.
  void MakeLocalOnly(uint32_t block);
  // Blocks held by `worker` go back to pending; returns them.
  std::vector<uint32_t> Release(uint64_t worker);
  // Blocks held by a remote worker past their deadline go back to pending; returns them.
  std::vector<uint32_t> Expire(Clock::time_point now);
  // A backup task: a block leased to a remote worker at or before `leased_before`, the
  // longest-held such, is handed to the server's threads (kLocal) as well: its worker's
  // result still counts if it comes first (Claim), and it is no longer released with its
  // worker. The block and the worker it was leased to; nullopt when there is none.
  struct Backup {
    uint32_t block = 0;
    uint64_t worker = 0;
    Clock::time_point leased_at;
  };
  std::optional<Backup> TakeBackup(Clock::time_point leased_before);
  // Who holds a block now (nullopt when it is not leased).
  std::optional<uint64_t> Holder(uint32_t block) const;

  bool AllDone() const { return done_ == states_.size(); }
  bool HasPending() const { return !pending_.empty(); }
  size_t remaining() const { return states_.size() - done_; }

 private:
  enum class State { kPending, kLeased, kClaimed, kDone };
  struct Entry {
    State state = State::kPending;
    uint64_t holder = 0;
    Clock::time_point deadline{};
    Clock::time_point leased_at{};
    bool local_only = false;
  };
  void Requeue(uint32_t block);

  std::map<uint32_t, Entry> states_;
  std::deque<uint32_t> pending_;  // may hold stale entries (skipped on Take)
  size_t done_ = 0;
};

}  // namespace radflux
