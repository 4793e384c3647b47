// `radflux solve SCENE --view`: a local solve showing itself in the browser, the same page
// as `radflux view JOB` (at /job/local/), fed from the solver's callbacks instead of gRPC.
#pragma once

#include <future>
#include <memory>
#include <thread>

#include "client/job_fetch.h"
#include "client/job_progress.h"
#include "client/solve_command.h"
#include "client/view/view_state.h"
#include "solver/mesh/patch_clusters.h"

namespace radflux::cli {

class SolveView : public SolveObserver {
 public:
  explicit SolveView(int port) : port_(port) {}
  ~SolveView() override;
  // Meshes the scene as the solve will (uniform), then serves the page and prints its URL.
  absl::Status Start(const Scene& scene, const JobOptions& options) override;
  // Progress events at most every 100 ms (and the last); a snapshot at most every 100 ms,
  // encoded on the solver's thread (float16 and the auto exposure: ~0.1 ms per 2,000
  // patches).
  void Phase(int64_t done, int64_t total) override;
  void Iteration(const SolveProgress& p) override;
  void Finish(const JobResult& result, const nlohmann::json& report) override;
  void ServeUntilStopped() override;

 private:
  // True when `force` or 100 ms passed since the last true of `last`.
  static bool Due(std::chrono::steady_clock::time_point& last, bool force);
  const int port_;
  std::shared_ptr<ViewState> state_ = std::make_shared<ViewState>();
  std::unique_ptr<JobProgress> words_;
  PatchClusters clusters_;  // the job's groups of patches: snapshots are per group
  std::thread server_;
  std::chrono::steady_clock::time_point last_event_, last_snapshot_;
};

}  // namespace radflux::cli
