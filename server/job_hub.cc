#include "server/job_hub.h"

#include <condition_variable>
#include <deque>
#include <thread>
#include <utility>

#include "server/proto_convert.h"

namespace radflux {

void JobHub::Publish(v1::JobEvent event) {
  {
    std::lock_guard lock(mu_);
    event.set_sequence(base_ + events_.size() + 1);
    event.set_job_id(job_id_);
    events_.push_back({event.sequence(), event.state(),
                       std::make_shared<const std::string>(event.SerializeAsString())});
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

bool JobHub::NextEvent(uint64_t after, HubEvent* out) const {
  std::lock_guard lock(mu_);
  const uint64_t index = after > base_ ? after - base_ : 0;
  if (index >= events_.size()) return false;
  *out = events_[index];
  return true;
}

bool JobHub::NewestSnapshot(int min_iteration, SnapshotData* out) const {
  std::lock_guard lock(mu_);
  if (!snapshot_.radiosity || snapshot_.iteration < min_iteration) return false;
  *out = snapshot_;
  return true;
}

EventWire JobHub::EncodedSnapshot(const SnapshotData& snapshot, const std::vector<int>& bands,
                                  v1::SnapshotFormat format) {
  std::string key = std::to_string(static_cast<int>(format)) + ":";
  for (int b : bands) key += std::to_string(b) + ",";
  std::lock_guard lock(encoded_mu_);
  Encoded& entry = encoded_[key];
  if (entry.source != snapshot.radiosity || !entry.message) {
    entry.source = snapshot.radiosity;
    v1::JobEvent only_snapshot;
    *only_snapshot.mutable_snapshot() =
        ToProtoSnapshot(snapshot.iteration, *snapshot.radiosity, bands, format);
    entry.message = std::make_shared<const std::string>(only_snapshot.SerializeAsString());
  }
  return entry.message;
}

bool JobHub::closed() const {
  std::lock_guard lock(mu_);
  return closed_;
}

uint64_t JobHub::last_sequence() const {
  std::lock_guard lock(mu_);
  return base_ + events_.size();
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

namespace {

// One thread that runs the wakes of every hub, in the order they were scheduled.
class Notifier {
 public:
  static Notifier& Get() {
    static Notifier notifier;
    return notifier;
  }
  void Post(std::shared_ptr<JobHub> hub, void (JobHub::*run)()) {
    {
      std::lock_guard lock(mu_);
      queue_.emplace_back(std::move(hub), run);
    }
    cv_.notify_one();
  }
  ~Notifier() {
    {
      std::lock_guard lock(mu_);
      stopping_ = true;
    }
    cv_.notify_one();
    thread_.join();
  }

 private:
  Notifier() : thread_([this] { Loop(); }) {}
  void Loop() {
    for (;;) {
      std::pair<std::shared_ptr<JobHub>, void (JobHub::*)()> next;
      {
        std::unique_lock lock(mu_);
        cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;
        next = std::move(queue_.front());
        queue_.pop_front();
      }
      ((*next.first).*next.second)();
    }
  }

  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::pair<std::shared_ptr<JobHub>, void (JobHub::*)()>> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace

void JobHub::WakeAll() {
  {
    std::lock_guard lock(mu_);
    if (wake_pending_ || subscribers_.empty()) return;
    wake_pending_ = true;
  }
  Notifier::Get().Post(shared_from_this(), &JobHub::RunWakes);
}

void JobHub::RunWakes() {
  std::vector<std::function<void()>> wakes;
  {
    std::lock_guard lock(mu_);
    wake_pending_ = false;
    for (const auto& [id, wake] : subscribers_) wakes.push_back(wake);
  }
  for (const auto& wake : wakes) wake();
}

}  // namespace radflux
