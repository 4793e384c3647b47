#include "client/job_progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace radflux::cli {
namespace {

std::string PhaseWords(const v1::JobEvent& event) {
  switch (event.state()) {
    case v1::JOB_STATE_QUEUED: return "queued";
    case v1::JOB_STATE_SUCCEEDED:
      if (event.has_converged() && !event.converged()) return "stopped short of its tolerance";
      if (event.has_energy_balance_ok() && !event.energy_balance_ok())
        return "succeeded, energy balance off";
      return "succeeded";
    case v1::JOB_STATE_FAILED: return "failed";
    case v1::JOB_STATE_CANCELLED: return "cancelled";
    default: break;
  }
  switch (event.phase()) {
    case v1::PHASE_PREPARE: return "preparing the scene";
    case v1::PHASE_ROWS: return "computing form factors";
    case v1::PHASE_SOLVE: return "solving";
    case v1::PHASE_DONE: return "writing the result";
    default: return "running";
  }
}

// 1234567 -> "1.2M".
std::string Rate(double per_second) {
  if (per_second >= 1e9) return absl::StrFormat("%.1fG", per_second / 1e9);
  if (per_second >= 1e6) return absl::StrFormat("%.1fM", per_second / 1e6);
  if (per_second >= 1e3) return absl::StrFormat("%.1fk", per_second / 1e3);
  return absl::StrFormat("%.0f", per_second);
}

}  // namespace

std::string DescribeSeconds(double seconds) {
  const int64_t s = std::llround(std::max(0.0, seconds));
  if (s < 60) return absl::StrCat(s, " s");
  if (s < 3600) return absl::StrCat(s / 60, " min ", s % 60, " s");
  return absl::StrCat(s / 3600, " h ", s % 3600 / 60, " min");
}

double JobProgress::SolveFraction(double residual) const {
  if (tolerance_ <= 0 || residual <= 0 || first_residual_ <= tolerance_) return -1;
  const double f = std::log(first_residual_ / residual) / std::log(first_residual_ / tolerance_);
  return std::clamp(f, 0.0, 1.0);
}

ProgressWords JobProgress::Update(const v1::JobEvent& event,
                                  std::chrono::steady_clock::time_point now) {
  ProgressWords w;
  w.phase = PhaseWords(event);
  if (!event.message().empty() && event.state() != v1::JOB_STATE_RUNNING) {
    w.detail = event.message();
  }
  const v1::Progress& p = event.progress();
  if (event.state() == v1::JOB_STATE_SUCCEEDED) w.fraction = 1;
  if (event.state() != v1::JOB_STATE_RUNNING) return w;
  if (event.phase() == v1::PHASE_ROWS && p.rows_total() > 0) {
    w.fraction = static_cast<double>(p.rows_done()) / static_cast<double>(p.rows_total());
    w.eta_seconds = p.eta_seconds();
    w.detail = absl::StrCat("rows ", p.rows_done(), "/", p.rows_total());
    if (p.rays_per_second() > 0) absl::StrAppend(&w.detail, ", ", Rate(p.rays_per_second()), " rays/s");
  } else if (event.phase() == v1::PHASE_SOLVE && p.iteration() > 0) {
    if (first_residual_ <= 0 && p.residual() > 0) {
      first_residual_ = p.residual();
      first_time_ = now;
    }
    w.fraction = SolveFraction(p.residual());
    const double elapsed = std::chrono::duration<double>(now - first_time_).count();
    if (w.fraction > 0.02 && w.fraction < 1) w.eta_seconds = elapsed * (1 - w.fraction) / w.fraction;
    w.detail = absl::StrFormat("iteration %d, residual %.2e", p.iteration(), p.residual());
    if (tolerance_ > 0) absl::StrAppend(&w.detail, absl::StrFormat(" (goal %.0e)", tolerance_));
  }
  if (w.eta_seconds > 0) absl::StrAppend(&w.detail, ", ETA ", DescribeSeconds(w.eta_seconds));
  return w;
}

}  // namespace radflux::cli
