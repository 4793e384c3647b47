// JobHub: the live event history of one job, shared by the job's runner (which
// publishes) and its watchers (which read at their own pace). Events are kept in order
// with sequence numbers base + 1, base + 2, ... (base 0 for a new job; a history rebuilt
// after a restart starts above every number an earlier history used); snapshots are not: only the
// newest is kept, so a slow watcher skips superseded snapshots and never holds the job back.
// Thread-safe.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "radflux/v1/job.pb.h"
#include "server/jobs/wake_schedule.h"
#include "solver/core/bands.h"

namespace radflux {

// Serialized bytes of a JobEvent (or of a part of one), shared by every watcher sending them.
using EventWire = std::shared_ptr<const std::string>;

// An event of the history as watchers send it: serialized once, when published.
struct HubEvent {
  uint64_t sequence = 0;
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  EventWire wire;
};

// B of every patch at one solver iteration.
struct SnapshotData {
  int iteration = 0;
  std::shared_ptr<const std::vector<Rgb>> radiosity;
};

// Copies a SUCCEEDED job's verdict (Job.converged, Job.energy_balance_ok, where set) onto
// the job's final event.
inline void CopyVerdict(const v1::Job& job, v1::JobEvent& event) {
  if (job.has_converged()) event.set_converged(job.converged());
  if (job.has_energy_balance_ok()) event.set_energy_balance_ok(job.energy_balance_ok());
}

class JobHub : public std::enable_shared_from_this<JobHub> {
 public:
  using Clock = WakeSchedule::Clock;
  // Watchers hear of a change at most this long after it by default, the job's end at once
  // (WakeSchedule): a round of writes to N watchers costs the server about as much with one
  // event as with several (each watcher's write, its TCP send and the thread wake-ups it
  // causes), so the events of an interval share a round (bench/watcher_cost.sh).
  static constexpr std::chrono::milliseconds kWakeInterval{250};

  // `base`: the sequence number before the first event (see JobStore::NextHistoryBase).
  explicit JobHub(std::string job_id, uint64_t base = 0,
                  Clock::duration wake_interval = kWakeInterval)
      : job_id_(std::move(job_id)), base_(base), wakes_(wake_interval) {}

  // Appends `event` with the next sequence number and wakes the watchers.
  void Publish(v1::JobEvent event);
  // Replaces the newest snapshot and wakes the watchers.
  void PublishSnapshot(SnapshotData snapshot);
  // Marks the history complete (its last event is terminal) and wakes the watchers.
  void Close();

  // The first event with sequence > after, if there is one yet; for `after` below this
  // history's base (a number from an earlier history), its first event.
  bool NextEvent(uint64_t after, HubEvent* out) const;
  // The newest snapshot, if its iteration is at least min_iteration.
  bool NewestSnapshot(int min_iteration, SnapshotData* out) const;
  // `snapshot` with these bands and format as the serialized JobEvent that holds only it
  // (its `snapshot` field), encoded and serialized once and shared by every watcher asking
  // the same: the newest snapshot reaches N watchers at the cost of one encoding, each
  // watcher prefixing its own few header bytes. Never takes the lock the publisher needs.
  EventWire EncodedSnapshot(const SnapshotData& snapshot, const std::vector<int>& bands,
                            v1::SnapshotFormat format);
  bool closed() const;
  uint64_t last_sequence() const;

  // `wake` is called after changes, until Unsubscribe(returned id): on the hub's notifier
  // thread (one for all hubs), never on the publisher's, so that a job never does its
  // watchers' writes. A round starts `wake_interval` after the first change it carries, a
  // terminal event or Close at once (WakeSchedule). The hub must be owned by a shared_ptr.
  int Subscribe(std::function<void()> wake);
  void Unsubscribe(int id);

 private:
  // Schedules a round of wakes on the notifier thread (at once if `urgent`) unless one is
  // pending that starts no later.
  void WakeAll(bool urgent);
  // The round of wakes scheduled for `due` (notifier thread); nothing if another round
  // replaced it.
  void RunWakes(Clock::time_point due);

  const std::string job_id_;
  const uint64_t base_;
  mutable std::mutex mu_;
  std::vector<HubEvent> events_;  // events_[k].sequence == base_ + k + 1
  SnapshotData snapshot_;
  bool closed_ = false;
  WakeSchedule wakes_;
  int next_subscriber_ = 0;
  struct Encoded {
    std::shared_ptr<const std::vector<Rgb>> source;  // the snapshot it encodes
    EventWire message;
  };
  std::mutex encoded_mu_;                   // guards encoded_ (not mu_: encoding is slow)
  std::map<std::string, Encoded> encoded_;  // by format and bands (validated: a few keys)
  std::map<int, std::function<void()>> subscribers_;
};

}  // namespace radflux
