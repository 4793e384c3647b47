// JobProgress (client/job_progress.h): a job's events in words, with the fraction and ETA
// of the current phase computed as documented.
#include "client/job_progress.h"

#include <gtest/gtest.h>

namespace radflux::cli {
namespace {

using Clock = std::chrono::steady_clock;

v1::JobEvent Event(v1::JobState state, v1::Phase phase) {
  v1::JobEvent e;
  e.set_state(state);
  e.set_phase(phase);
  return e;
}

v1::JobEvent Solve(int iteration, double residual) {
  v1::JobEvent e = Event(v1::JOB_STATE_RUNNING, v1::PHASE_SOLVE);
  e.mutable_progress()->set_iteration(iteration);
  e.mutable_progress()->set_residual(residual);
  return e;
}

TEST(JobProgress, RowsAreAFractionWithTheServersEta) {
  JobProgress progress(1e-4);
  v1::JobEvent e = Event(v1::JOB_STATE_RUNNING, v1::PHASE_ROWS);
  e.mutable_progress()->set_rows_done(250);
  e.mutable_progress()->set_rows_total(1000);
  e.mutable_progress()->set_rays_per_second(2.5e6);
  e.mutable_progress()->set_eta_seconds(75);
  const ProgressWords w = progress.Update(e, Clock::now());
  EXPECT_EQ(w.phase, "computing form factors");
  EXPECT_DOUBLE_EQ(w.fraction, 0.25);
  EXPECT_EQ(w.detail, "rows 250/1000, 2.5M rays/s, ETA 1 min 15 s");
}

TEST(JobProgress, SolveFractionIsLogResidualProgressTowardTheTolerance) {
  JobProgress progress(1e-4);
  const Clock::time_point start = Clock::now();
  const ProgressWords first = progress.Update(Solve(1, 1e-1), start);
  EXPECT_EQ(first.phase, "solving");
  EXPECT_DOUBLE_EQ(first.fraction, 0);
  // From 1e-1 to 1e-2 of the way to 1e-4: one decade of three, in 2 s: 4 s left.
  const ProgressWords later = progress.Update(Solve(9, 1e-2), start + std::chrono::seconds(2));
  EXPECT_NEAR(later.fraction, 1.0 / 3, 1e-12);
  EXPECT_NEAR(later.eta_seconds, 4, 1e-9);
  EXPECT_EQ(later.detail, "iteration 9, residual 1.00e-02 (goal 1e-04), ETA 4 s");
  EXPECT_DOUBLE_EQ(progress.Update(Solve(12, 1e-5), start).fraction, 1);
}

TEST(JobProgress, UnknownToleranceHasNoSolveFraction) {
  JobProgress progress(0);
  progress.Update(Solve(1, 1e-1), Clock::now());
  EXPECT_LT(progress.Update(Solve(2, 1e-2), Clock::now()).fraction, 0);
}

TEST(JobProgress, EndStatesInWords) {
  JobProgress progress(1e-4);
  EXPECT_EQ(progress.Update(Event(v1::JOB_STATE_QUEUED, v1::PHASE_UNSPECIFIED), Clock::now()).phase,
            "queued");
  v1::JobEvent done = Event(v1::JOB_STATE_SUCCEEDED, v1::PHASE_DONE);
  EXPECT_EQ(progress.Update(done, Clock::now()).phase, "succeeded");
  EXPECT_DOUBLE_EQ(progress.Update(done, Clock::now()).fraction, 1);
  done.set_converged(false);
  EXPECT_EQ(progress.Update(done, Clock::now()).phase, "stopped short of its tolerance");
  v1::JobEvent failed = Event(v1::JOB_STATE_FAILED, v1::PHASE_ROWS);
  failed.set_message("out of memory");
  const ProgressWords w = progress.Update(failed, Clock::now());
  EXPECT_EQ(w.phase, "failed");
  EXPECT_EQ(w.detail, "out of memory");
}

TEST(DescribeSeconds, ForAPerson) {
  EXPECT_EQ(DescribeSeconds(42.4), "42 s");
  EXPECT_EQ(DescribeSeconds(185), "3 min 5 s");
  EXPECT_EQ(DescribeSeconds(7800), "2 h 10 min");
}

}  // namespace
}  // namespace radflux::cli
