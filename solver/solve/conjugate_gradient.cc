// Preconditioned conjugate gradient on the symmetric form. Row i of B - rho F B = E times
// A_i / rho_i gives M B = (A / rho) E with M = D - S, D = diag(A / rho), S = sym(A F):
// symmetric, and positive definite for reciprocal rows (rho_i > 0); patches with rho_i = 0
// are known (B_i = E_i). The preconditioner is D, M's diagonal but for S_ii (0 but for a
// group that sees itself, face_grouping.h), z = D^-1 r = rho r / A, so the preconditioned
// operator is I - rho A^-1 S, which is I - rho F for reciprocal rows: its eigenvalues lie in
// [1 - rho_max, 1 + rho_max] whatever the ratio of the largest to the smallest patch area.
// CG runs on corrections: its right-hand side is the scaled true residual
// (A / rho)(E + rho F B - B) of the ORIGINAL rows, measured every iteration (one SpMV).
// When the rows are not reciprocal, S differs from A F and the CG residual falls below
// the true one; the lane then restarts from the true residual (defect correction).
// Sampled rows can make M indefinite as rho -> 1; CG then gives up (p^T M p <= 0, a
// residual that grows for kGrowthLimit iterations in a row, or one that stalls) and leaves
// the best B it reached, with the reason, for Solve() to continue with gauss_seidel.
#include <cmath>

#include "absl/strings/str_format.h"
#include "solver/solve/methods.h"
#include "solver/solve/stopping.h"
#include "solver/solve/symmetric_form.h"

namespace radflux {
namespace {

// Restart a lane when its CG residual (unscaled) is below this fraction of the true one.
constexpr double kRestartRatio = 0.1;
// Give up when the true residual grew this many iterations in a row...
constexpr int kGrowthLimit = 5;
// ...or did not halve its best value in this many iterations.
constexpr int kStallIterations = 100;

struct CgState {
  std::vector<Rgb> r, z, p, q, rt;  // CG residual, rho r / A, direction, M p, true residual
  Rgb rz{};                         // r.z per lane
  std::array<bool, kBands> active{};
};

bool Unknown(const BandSystem& bands, int64_t i, int k) { return bands.rho[i][k] > 0; }

// q = M p for every lane.
void MultiplyM(const BandSystem& bands, const SymmetricForm& s, CgState& st) {
  const std::vector<double>& area = *bands.area;
  ParallelFor(bands.n, kSolveBlock, bands.threads, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      Rgb sp{};
      for (uint64_t e = s.row_begin[i]; e < s.row_begin[i + 1]; ++e)
        for (int k = 0; k < bands.lanes; ++k) sp[k] += s.value[e] * st.p[s.col[e]][k];
      for (int k = 0; k < bands.lanes; ++k)
        st.q[i][k] = Unknown(bands, i, k) ? area[i] / bands.rho[i][k] * st.p[i][k] - sp[k] : 0;
    }
  });
}

// z = rho r / A on every lane; returns per lane r.z (first) and ||z||_A^2, the CG
// residual in the original scale.
std::pair<Rgb, Rgb> Precondition(const BandSystem& bands, CgState& st) {
  const std::vector<double>& area = *bands.area;
  Rgb rz{}, zz{};
  for (int64_t begin = 0; begin < bands.n; begin += kVectorBlock) {  // fixed order
    const int64_t end = std::min<int64_t>(bands.n, begin + kVectorBlock);
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k) {
        st.z[i][k] = st.r[i][k] * bands.rho[i][k] / area[i];
        rz[k] += st.r[i][k] * st.z[i][k];
        zz[k] += area[i] * st.z[i][k] * st.z[i][k];
      }
  }
  return {rz, zz};
}

// r = (A / rho) * true residual, z = rho r / A, p = z for lane k (0 on known patches).
void RestartLane(const BandSystem& bands, int k, CgState& st) {
  const std::vector<double>& area = *bands.area;
  double rz = 0;
  for (uint32_t i = 0; i < bands.n; ++i) {
    const bool unknown = Unknown(bands, i, k);
    st.r[i][k] = unknown ? area[i] / bands.rho[i][k] * st.rt[i][k] : 0;
    st.z[i][k] = unknown ? st.rt[i][k] : 0;
    st.p[i][k] = st.z[i][k];
    rz += st.r[i][k] * st.z[i][k];
  }
  st.rz[k] = rz;
  st.active[k] = rz > 0;
}

// x += alpha p, r -= alpha q on active lanes, alpha = r.z / p.q. Returns false (and
// changes nothing) when p.q <= 0 on an active lane: M is not positive definite.
bool Step(const BandSystem& bands, CgState& st, std::vector<Rgb>& x) {
  const Rgb pq =
      ReduceBlocks(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
        Rgb s{};
        for (int64_t i = begin; i < end; ++i)
          for (int k = 0; k < bands.lanes; ++k) s[k] += st.p[i][k] * st.q[i][k];
        return s;
      });
  Rgb alpha{};
  for (int k = 0; k < bands.lanes; ++k) {
    if (!st.active[k]) continue;
    if (!(pq[k] > 0)) return false;
    alpha[k] = st.rz[k] / pq[k];
  }
  ParallelFor(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k) {
        x[i][k] += alpha[k] * st.p[i][k];
        st.r[i][k] -= alpha[k] * st.q[i][k];
      }
  });
  return true;
}

// After a step: freeze converged lanes, restart drifted ones, else the next direction.
void NextDirections(const BandSystem& bands, const Rgb& measure, double tolerance, CgState& st) {
  const auto [rz, zz] = Precondition(bands, st);
  const Rgb true_norm2 = AreaDot(bands, st.rt, st.rt);
  Rgb beta{};
  for (int k = 0; k < bands.lanes; ++k) {
    if (!st.active[k]) continue;
    if (measure[k] <= tolerance) {
      st.active[k] = false;
    } else if (std::sqrt(zz[k]) < kRestartRatio * std::sqrt(true_norm2[k]) || !(rz[k] > 0)) {
      RestartLane(bands, k, st);
      continue;
    }
    beta[k] = st.rz[k] > 0 ? rz[k] / st.rz[k] : 0;
    st.rz[k] = rz[k];
  }
  ParallelFor(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k)
        if (st.active[k]) st.p[i][k] = st.z[i][k] + beta[k] * st.p[i][k];
  });
}

// Watches the true residual for divergence and stagnation; keeps the best iterate.
class DivergenceWatch {
 public:
  // Records the residual of `b`; returns why CG should give up, or "" to go on.
  std::string Observe(int iteration, double residual, const std::vector<Rgb>& b) {
    if (residual < best_) {
      if (residual <= 0.5 * halved_at_) {
        halved_at_ = residual;
        halved_iteration_ = iteration;
      }
      best_ = residual;
      best_b_ = b;
    }
    growth_ = residual > last_ ? growth_ + 1 : 0;
    last_ = residual;
    if (growth_ >= kGrowthLimit) {
      return absl::StrFormat("residual grew %d iterations in a row (to %.3g; best %.3g)", growth_,
                             residual, best_);
    }
    if (iteration - halved_iteration_ >= kStallIterations) {
      return absl::StrFormat("residual stalled at %.3g (not halved in %d iterations)", best_,
                             kStallIterations);
    }
    return "";
  }
  // The iterate with the smallest residual seen (empty before the first Observe).
  const std::vector<Rgb>& best() const { return best_b_; }

 private:
  double best_ = INFINITY, last_ = INFINITY, halved_at_ = INFINITY;
  int growth_ = 0, halved_iteration_ = 0;
  std::vector<Rgb> best_b_;
};

}  // namespace

absl::Status SolveConjugateGradient(const BandSystem& bands, const SolverOptions& options,
                                    const SolveCallback& callback, std::vector<Rgb>& b,
                                    SolveResult& result) {
  const SymmetricForm s = BuildSymmetricForm(*bands.f, *bands.area);
  result.reciprocity_error = s.reciprocity_error;
  result.one_sided_pairs = s.one_sided_pairs;
  for (uint32_t i = 0; i < bands.n; ++i)
    for (int k = 0; k < bands.lanes; ++k)
      if (!Unknown(bands, i, k)) b[i][k] = bands.emission[i][k];
  CgState st;
  for (std::vector<Rgb>* v : {&st.r, &st.z, &st.p, &st.q}) v->assign(bands.n, Rgb{});
  ResidentLaneResiduals(bands, b, &st.rt);
  for (int k = 0; k < bands.lanes; ++k) RestartLane(bands, k, st);
  IterationMonitor monitor(bands, options, callback, result);
  DivergenceWatch watch;
  while (!monitor.ShouldStop()) {
    MultiplyM(bands, s, st);
    if (!Step(bands, st, b)) {
      result.fallback_reason = absl::StrFormat(
          "p^T M p <= 0 at iteration %d: the symmetrised rows are indefinite (rows not "
          "reciprocal enough for this rho)",
          monitor.iteration() + 1);
      break;
    }
    const Rgb measure = ResidentLaneResiduals(bands, b, &st.rt);
    const double residual = MaxOverLanes(bands, measure);
    if (monitor.Record(residual, residual, 0, b)) return absl::OkStatus();
    result.fallback_reason = watch.Observe(monitor.iteration(), residual, b);
    if (!result.fallback_reason.empty()) break;
    NextDirections(bands, measure, options.tolerance, st);
  }
  if (!result.fallback_reason.empty() && !watch.best().empty()) b = watch.best();
  return absl::OkStatus();
}

}  // namespace radflux
