// What the browser view shows of one job, shared between the thread that follows the job
// over gRPC (the writer) and the HTTP threads (readers). Latest wins: the writer replaces
// the newest snapshot and never waits for a reader; a reader that was slow sees only the
// newest state when it looks again, never a backlog.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "nlohmann/json.hpp"

namespace radflux::cli {

// The newest B of a job for the page: float16 per patch and band (little-endian,
// patch-major, bands red green blue) and the auto exposure that the PNG writer would use.
struct ViewSnapshot {
  int iteration = 0;
  uint64_t serial = 0;          // 1 for the job's first snapshot, +1 each (set by ViewState)
  std::string half_rgb;         // 6 bytes per patch
  double exposure_scale = 1.0;  // AutoExposureScale of radiance B/pi (tone_map.h)
};

class ViewState {
 public:
  // Static parts, set once before the job is followed: the page's "info" JSON and the mesh.
  void SetInfo(nlohmann::json info, std::string mesh);
  // One progress event: "phase", "fraction", "eta_seconds", "detail", "state", ... fields;
  // (iteration, residual) joins the residual plot when residual > 0.
  void Publish(nlohmann::json progress, int iteration, double residual);
  // Replaces the newest snapshot, numbering it.
  void PublishSnapshot(ViewSnapshot snapshot);
  // The job ended: its report JSON (may be empty) and the lit mesh as a GLB (may be empty).
  void End(std::string report, std::string glb);
  // The error that stops the view of this job (the page shows it).
  void Fail(const std::string& message);

  // Waits until the state is newer than `version` or `timeout` passes; returns the version.
  uint64_t WaitNewer(uint64_t version, std::chrono::milliseconds timeout);
  // One message for the page: progress, the residual points from index `*cursor` on
  // (advanced past them), the newest snapshot's serial and iteration, whether the job ended.
  std::string Message(size_t* cursor) const;
  // The newest snapshot (null before the first).
  std::shared_ptr<const ViewSnapshot> Snapshot() const;
  // Copies of what SetInfo and End set ("{}" / empty before), and whether the job ended.
  std::string info() const;
  std::string mesh() const;
  std::string report() const;
  std::string glb() const;
  bool ended() const;

 private:
  void Changed();  // under mu_: bumps the version and wakes the readers
  mutable std::mutex mu_;
  std::condition_variable changed_;
  uint64_t version_ = 0;
  nlohmann::json info_, progress_ = nlohmann::json::object();
  std::string mesh_, report_, glb_, error_;
  std::vector<std::pair<int, double>> residuals_;  // (iteration, residual), in arrival order
  std::shared_ptr<const ViewSnapshot> snapshot_;
  uint64_t snapshots_ = 0;  // published so far
  bool ended_ = false;
};

}  // namespace radflux::cli
