// Conjugate gradient on the symmetric form. Row i of B - rho F B = E times A_i / rho_i
// gives M B = (A / rho) E with M = diag(A / rho) - S, S = sym(A F): symmetric positive
// definite over the unknowns (rho_i > 0); patches with rho_i = 0 are known (B_i = E_i).
// CG runs on corrections: its right-hand side is the scaled true residual
// (A / rho)(E + rho F B - B) of the ORIGINAL rows, measured every iteration (one SpMV).
// When the rows are not reciprocal, S differs from A F and the CG residual falls below
// the true one; the lane then restarts from the true residual (defect correction), so
// the iteration still converges to the solution of the original rows.
#include <cmath>

#include "solver/solve/methods.h"
#include "solver/solve/stopping.h"
#include "solver/solve/symmetric_form.h"

namespace radflux {
namespace {

// Restart a lane when its CG residual (unscaled) is below this fraction of the true one.
constexpr double kRestartRatio = 0.1;

struct CgState {
  std::vector<Rgb> r, p, q, rt;  // CG residual, direction, M p, true residual
  Rgb rr{};                      // r.r per lane
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

// Per lane: r.r (first) and ||r rho / A||_A^2, the CG residual in the original scale.
std::pair<Rgb, Rgb> ResidualNorms(const BandSystem& bands, const std::vector<Rgb>& r) {
  const std::vector<double>& area = *bands.area;
  Rgb plain = ReduceBlocks(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
    Rgb s{};
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k) s[k] += r[i][k] * r[i][k];
    return s;
  });
  Rgb unscaled =
      ReduceBlocks(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
        Rgb s{};
        for (int64_t i = begin; i < end; ++i)
          for (int k = 0; k < bands.lanes; ++k) {
            const double v = r[i][k] * bands.rho[i][k];
            s[k] += v * v / area[i];
          }
        return s;
      });
  return {plain, unscaled};
}

// r = p = (A / rho) * true residual for lane k (0 on known patches).
void RestartLane(const BandSystem& bands, int k, CgState& st) {
  const std::vector<double>& area = *bands.area;
  for (uint32_t i = 0; i < bands.n; ++i) {
    st.r[i][k] = Unknown(bands, i, k) ? area[i] / bands.rho[i][k] * st.rt[i][k] : 0;
    st.p[i][k] = st.r[i][k];
  }
  double rr = 0;
  for (uint32_t i = 0; i < bands.n; ++i) rr += st.r[i][k] * st.r[i][k];
  st.rr[k] = rr;
  st.active[k] = rr > 0;
}

// x += alpha p, r -= alpha q on active lanes; alpha = rr / p.q (restart on breakdown).
void Step(const BandSystem& bands, CgState& st, std::vector<Rgb>& x) {
  const Rgb pq =
      ReduceBlocks(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
        Rgb s{};
        for (int64_t i = begin; i < end; ++i)
          for (int k = 0; k < bands.lanes; ++k) s[k] += st.p[i][k] * st.q[i][k];
        return s;
      });
  Rgb alpha{};
  for (int k = 0; k < bands.lanes; ++k) alpha[k] = st.active[k] && pq[k] > 0 ? st.rr[k] / pq[k] : 0;
  ParallelFor(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k) {
        x[i][k] += alpha[k] * st.p[i][k];
        st.r[i][k] -= alpha[k] * st.q[i][k];
      }
  });
}

// After a step: freeze converged lanes, restart drifted ones, else the next direction.
void NextDirections(const BandSystem& bands, const Rgb& relative, double tolerance, CgState& st) {
  const auto [rr, unscaled] = ResidualNorms(bands, st.r);
  Rgb beta{};
  for (int k = 0; k < bands.lanes; ++k) {
    if (!st.active[k]) continue;
    const double true_norm = relative[k] * bands.emission_norm[k];
    if (relative[k] <= tolerance) {
      st.active[k] = false;
    } else if (std::sqrt(unscaled[k]) < kRestartRatio * true_norm || !(rr[k] > 0)) {
      RestartLane(bands, k, st);
      continue;
    }
    beta[k] = st.rr[k] > 0 ? rr[k] / st.rr[k] : 0;
    st.rr[k] = rr[k];
  }
  ParallelFor(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < bands.lanes; ++k)
        if (st.active[k]) st.p[i][k] = st.r[i][k] + beta[k] * st.p[i][k];
  });
}

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
  st.r.assign(bands.n, Rgb{});
  st.p.assign(bands.n, Rgb{});
  st.q.assign(bands.n, Rgb{});
  ResidentLaneResiduals(bands, b, &st.rt);
  for (int k = 0; k < bands.lanes; ++k) RestartLane(bands, k, st);
  IterationMonitor monitor(bands, options, callback, result);
  while (!monitor.ShouldStop()) {
    MultiplyM(bands, s, st);
    Step(bands, st, b);
    const Rgb relative = ResidentLaneResiduals(bands, b, &st.rt);
    const double residual = MaxOverLanes(bands, relative);
    if (monitor.Record(residual, residual, 0, b)) break;
    NextDirections(bands, relative, options.tolerance, st);
  }
  return absl::OkStatus();
}

}  // namespace radflux
