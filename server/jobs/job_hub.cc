#include "server/jobs/job_hub.h"

#include <condition_variable>
#include <map>
#include <thread>
#include <utility>

#include "wire/proto_convert.h"

namespace radflux {

void JobHub::Publish(v1::JobEvent event) {
  const bool terminal = IsTerminal(event.state());
  {
    std::lock_guard lock(mu_);
    event.set_sequence(base_ + events_.size() + 1);
    event.set_job_id(job_id_);
    events_.push_back({event.sequence(), event.state(),
                       std::make_shared<const std::string>(event.SerializeAsString())});
  }
  WakeAll(terminal);
}

void JobHub::PublishSnapshot(SnapshotData snapshot) {
  {
    std::lock_guard lock(mu_);
    snapshot_ = std::move(snapshot);
  }
  WakeAll(false);
}

void JobHub::Close() {
  {
    std::lock_guard lock(mu_);
    closed_ = true;
  }
  WakeAll(true);
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

// One thread that runs the wakes of every hub, each when it is due (in the order they
// were scheduled among those due at the same time).
class Notifier {
 public:
  using Clock = JobHub::Clock;
  static Notifier& Get() {
    static Notifier notifier;
    return notifier;
  }
  void Post(Clock::time_point due, std::function<void()> run) {
    {
      std::lock_guard lock(mu_);
      queue_.emplace(due, std::move(run));
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
  // Runs each round when due; at shutdown, the ones already due.
  void Loop() {
    for (;;) {
      std::function<void()> next;
      {
        std::unique_lock lock(mu_);
        for (;;) {
          if (!queue_.empty() && queue_.begin()->first <= Clock::now()) break;
          if (stopping_) return;
          if (queue_.empty()) {
            cv_.wait(lock);
          } else {
            cv_.wait_until(lock, queue_.begin()->first);
          }
        }
        next = std::move(queue_.begin()->second);
        queue_.erase(queue_.begin());
      }
      next();
    }
  }

  std::mutex mu_;
  std::condition_variable cv_;
  std::multimap<Clock::time_point, std::function<void()>> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace

void JobHub::WakeAll(bool urgent) {
  std::optional<Clock::time_point> due;
  {
    std::lock_guard lock(mu_);
    if (subscribers_.empty()) return;
    due = wakes_.Request(Clock::now(), urgent);
  }
  if (due) Notifier::Get().Post(*due, [hub = shared_from_this(), due] { hub->RunWakes(*due); });
}

void JobHub::RunWakes(Clock::time_point due) {
  std::vector<std::function<void()>> wakes;
  {
    std::lock_guard lock(mu_);
    if (!wakes_.Start(due)) return;  // replaced by a sooner round
    for (const auto& [id, wake] : subscribers_) wakes.push_back(wake);
  }
  for (const auto& wake : wakes) wake();
}

}  // namespace radflux
