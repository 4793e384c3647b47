#include "server/job_hub.h"

namespace radflux {

void JobHub::Publish(v1::JobEvent event) {
  {
    std::lock_guard lock(mu_);
    event.set_sequence(events_.size() + 1);
    event.set_job_id(job_id_);
    events_.push_back(std::move(event));
  }
  WakeAll();
}

void JobHub::PublishSnapshot(SnapshotData snapshot) {
  {
    std::lock_guard lock(mu_);
    snapshot_ = std::move(snapshot);
  }
  WakeAll();
}

void JobHub::Close() {
  {
    std::lock_guard lock(mu_);
    closed_ = true;
  }
  WakeAll();
}

bool JobHub::NextEvent(uint64_t after, v1::JobEvent* out) const {
  std::lock_guard lock(mu_);
  if (after >= events_.size()) return false;
  *out = events_[after];
  return true;
}

bool JobHub::NewestSnapshot(int min_iteration, SnapshotData* out) const {
  std::lock_guard lock(mu_);
  if (!snapshot_.radiosity || snapshot_.iteration < min_iteration) return false;
  *out = snapshot_;
  return true;
}

bool JobHub::closed() const {
  std::lock_guard lock(mu_);
  return closed_;
}

uint64_t JobHub::last_sequence() const {
  std::lock_guard lock(mu_);
  return events_.size();
}

int JobHub::Subscribe(std::function<void()> wake) {
  std::lock_guard lock(mu_);
  subscribers_.emplace(next_subscriber_, std::move(wake));
  return next_subscriber_++;
}

void JobHub::Unsubscribe(int id) {
  std::lock_guard lock(mu_);
  subscribers_.erase(id);
}

void JobHub::WakeAll() {
  std::vector<std::function<void()>> wakes;
  {
    std::lock_guard lock(mu_);
    for (const auto& [id, wake] : subscribers_) wakes.push_back(wake);
  }
  for (const auto& wake : wakes) wake();
}

}  // namespace radflux
