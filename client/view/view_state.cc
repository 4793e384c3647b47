#include "client/view/view_state.h"

namespace radflux::cli {

void ViewState::Changed() {
  ++version_;
  changed_.notify_all();
}

void ViewState::SetInfo(nlohmann::json info, std::string mesh) {
  std::lock_guard lock(mu_);
  info_ = std::move(info);
  mesh_ = std::move(mesh);
  Changed();
}

void ViewState::Publish(nlohmann::json progress, int iteration, double residual) {
  std::lock_guard lock(mu_);
  progress_ = std::move(progress);
  if (residual > 0 && (residuals_.empty() || residuals_.back().first != iteration)) {
    residuals_.emplace_back(iteration, residual);
  }
  Changed();
}

void ViewState::PublishSnapshot(ViewSnapshot snapshot) {
  std::lock_guard lock(mu_);
  snapshot.serial = ++snapshots_;
  snapshot_ = std::make_shared<const ViewSnapshot>(std::move(snapshot));
  Changed();
}

void ViewState::End(std::string report, std::string glb) {
  std::lock_guard lock(mu_);
  report_ = std::move(report);
  glb_ = std::move(glb);
  ended_ = true;
  Changed();
}

void ViewState::Fail(const std::string& message) {
  std::lock_guard lock(mu_);
  error_ = message;
  ended_ = true;
  Changed();
}

uint64_t ViewState::WaitNewer(uint64_t version, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mu_);
  changed_.wait_for(lock, timeout, [&] { return version_ > version; });
  return version_;
}

std::string ViewState::Message(size_t* cursor) const {
  std::lock_guard lock(mu_);
  nlohmann::json m = progress_;
  nlohmann::json points = nlohmann::json::array();
  for (size_t i = *cursor; i < residuals_.size(); ++i) {
    points.push_back({residuals_[i].first, residuals_[i].second});
  }
  *cursor = residuals_.size();
  m["residuals"] = std::move(points);
  m["snapshot_serial"] = snapshots_;
  m["snapshot_iteration"] = snapshot_ ? snapshot_->iteration : -1;
  m["ended"] = ended_;
  m["has_report"] = !report_.empty();
  m["has_glb"] = !glb_.empty();
  if (!error_.empty()) m["error"] = error_;
  return m.dump();
}

std::shared_ptr<const ViewSnapshot> ViewState::Snapshot() const {
  std::lock_guard lock(mu_);
  return snapshot_;
}

std::string ViewState::info() const {
  std::lock_guard lock(mu_);
  return info_.is_null() ? "{}" : info_.dump();
}

std::string ViewState::mesh() const {
  std::lock_guard lock(mu_);
  return mesh_;
}

std::string ViewState::report() const {
  std::lock_guard lock(mu_);
  return report_;
}

std::string ViewState::glb() const {
  std::lock_guard lock(mu_);
  return glb_;
}

bool ViewState::ended() const {
  std::lock_guard lock(mu_);
  return ended_;
}

}  // namespace radflux::cli
