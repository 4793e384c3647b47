// RecentMap: the values of the `capacity` most recently put keys, shared and immutable.
// What the server keeps warm between calls about the same thing: loaded scenes (SceneCache)
// and the results of the jobs that just succeeded (JobManager, for GetResult). A value is
// the one put under its key, or absent; never a stale one, since callers only put values
// that never change under their key. Thread-safe.
#pragma once

#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

namespace radflux {

template <typename V>
class RecentMap {
 public:
  explicit RecentMap(size_t capacity) : capacity_(capacity) {}

  // The value under `key`, or null.
  std::shared_ptr<const V> Get(const std::string& key) const {
    std::lock_guard lock(mu_);
    for (const auto& [k, value] : recent_) {
      if (k == key) return value;
    }
    return nullptr;
  }

  // Puts `value` under `key` as the most recent, dropping the least recent beyond capacity.
  void Put(const std::string& key, std::shared_ptr<const V> value) {
    std::lock_guard lock(mu_);
    recent_.emplace_front(key, std::move(value));
    if (recent_.size() > capacity_) recent_.pop_back();
  }

 private:
  const size_t capacity_;
  mutable std::mutex mu_;                                                // guards recent_
  std::deque<std::pair<std::string, std::shared_ptr<const V>>> recent_;  // newest first
};

}  // namespace radflux
