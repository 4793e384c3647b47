#include "solver/solve/stopping.h"

namespace radflux {

IterationMonitor::IterationMonitor(const BandSystem& bands, const SolverOptions& options,
                                   const SolveCallback& callback, SolveResult& result)
    : bands_(bands), options_(options), callback_(callback), result_(result) {}

bool IterationMonitor::ShouldStop() {
  if (options_.cancel != nullptr && options_.cancel->load(std::memory_order_relaxed)) {
    result_.cancelled = true;
    return true;
  }
  return iteration_ >= options_.max_iterations;
}

bool IterationMonitor::SnapshotDue() const {
  return options_.snapshot_every > 0 && (iteration_ + 1) % options_.snapshot_every == 0;
}

bool IterationMonitor::Record(double measure, double residual, double unshot_fraction,
                              const std::vector<Rgb>& display) {
  const bool snapshot = SnapshotDue();
  ++iteration_;
  result_.iterations = iteration_;
  result_.residual_history.push_back(measure);
  result_.converged = measure <= options_.tolerance;
  if (callback_) {
    SolveProgress progress;
    progress.iteration = iteration_;
    progress.residual = residual;
    progress.unshot_fraction = unshot_fraction;
    if (snapshot) {
      UnpackLanes(bands_, display, snapshot_);
      progress.snapshot = &snapshot_;
      progress.state = &snapshot_;
      if (state_b_ != nullptr) {
        UnpackLanes(bands_, *state_b_, state_);
        progress.state = &state_;
      }
      if (state_unshot_ != nullptr) {
        UnpackLanes(bands_, *state_unshot_, unshot_);
        progress.state_unshot = &unshot_;
      }
    }
    callback_(progress);
  }
  return result_.converged;
}

}  // namespace radflux
