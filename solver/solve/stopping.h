// IterationMonitor: the stopping rule and progress reporting shared by every method.
// A method asks ShouldStop() before each sweep (cancellation, max iterations) and
// calls Record() after it; Record() calls back every iteration and attaches a snapshot
// (all three bands) only every options.snapshot_every iterations.
#pragma once

#include <vector>

#include "solver/core/bands.h"
#include "solver/solve/band_system.h"
#include "solver/solve/solver.h"

namespace radflux {

class IterationMonitor {
 public:
  IterationMonitor(const BandSystem& bands, const SolverOptions& options,
                   const SolveCallback& callback, SolveResult& result);

  // True when no further sweep may start: cancelled (sets result.cancelled) or
  // max_iterations sweeps done. Checked once per sweep.
  bool ShouldStop();
  // Whether the iteration about to be recorded carries a snapshot.
  bool SnapshotDue() const;
  // Records one finished sweep with its stopping `measure` (residual, or unshot fraction
  // for southwell); `display` (lane values) is copied into the snapshot when one is due.
  // Returns true when measure <= tolerance (and sets result.converged).
  bool Record(double measure, double residual, double unshot_fraction,
              const std::vector<Rgb>& display);
  int iteration() const { return iteration_; }
  // Shooting methods: the iterate and unshot radiosity (lane values) the next Record
  // reports as SolveProgress::state / state_unshot when a snapshot is due (default: the
  // display values and no unshot).
  void SetShootingState(const std::vector<Rgb>* b, const std::vector<Rgb>* unshot) {
    state_b_ = b;
    state_unshot_ = unshot;
  }

 private:
  const BandSystem& bands_;
  const SolverOptions& options_;
  const SolveCallback& callback_;
  SolveResult& result_;
  int iteration_ = 0;
  std::vector<Rgb> snapshot_;
  const std::vector<Rgb>* state_b_ = nullptr;
  const std::vector<Rgb>* state_unshot_ = nullptr;
  std::vector<Rgb> state_, unshot_;
};

}  // namespace radflux
