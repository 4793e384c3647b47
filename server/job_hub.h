// JobHub: the live event history of one job, shared by the job's runner (which
// publishes) and its watchers (which read at their own pace). Events are kept in order
// with sequence numbers 1, 2, ...; snapshots are not: only the newest is kept, so a slow
// watcher skips superseded snapshots and never holds the job back. Thread-safe.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "radflux/v1/job.pb.h"
#include "solver/core/bands.h"

namespace radflux {

// B of every patch at one solver iteration.
struct SnapshotData {
  int iteration = 0;
  std::shared_ptr<const std::vector<Rgb>> radiosity;
};

class JobHub {
 public:
  explicit JobHub(std::string job_id) : job_id_(std::move(job_id)) {}

  // Appends `event` with the next sequence number and wakes the watchers.
  void Publish(v1::JobEvent event);
  // Replaces the newest snapshot and wakes the watchers.
  void PublishSnapshot(SnapshotData snapshot);
  // Marks the history complete (its last event is terminal) and wakes the watchers.
  void Close();

  // The first event with sequence > after, if there is one yet.
  bool NextEvent(uint64_t after, v1::JobEvent* out) const;
  // The newest snapshot, if its iteration is at least min_iteration.
  bool NewestSnapshot(int min_iteration, SnapshotData* out) const;
  bool closed() const;
  uint64_t last_sequence() const;

  // `wake` is called (outside the hub's lock, possibly on the runner's thread) after
  // every change, until Unsubscribe(returned id).
  int Subscribe(std::function<void()> wake);
  void Unsubscribe(int id);

 private:
  void WakeAll();

  const std::string job_id_;
  mutable std::mutex mu_;
  std::vector<v1::JobEvent> events_;  // events_[k].sequence() == k + 1
  SnapshotData snapshot_;
  bool closed_ = false;
  int next_subscriber_ = 0;
  std::map<int, std::function<void()>> subscribers_;
};

}  // namespace radflux
