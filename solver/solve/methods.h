// The solver methods behind Solve(). Each starts from the lane values in `b` (zero or
// the caller's warm start), leaves its final iterate there, and fills the iteration
// fields of `result` (iterations, residual_history, converged, cancelled) through an
// IterationMonitor. Solve() computes the final residual and unpacks the bands.
#pragma once

#include <vector>

#include "absl/status/status.h"
#include "solver/solve/band_system.h"
#include "solver/solve/solver.h"

namespace radflux {

// Gathering, all rows from the previous sweep: B <- E + rho F B.
absl::Status SolveJacobi(const BandSystem& bands, const SolverOptions& options,
                         const SolveCallback& callback, std::vector<Rgb>& b, SolveResult& result);
// Gathering in row order, each row using the rows already updated in this sweep.
absl::Status SolveGaussSeidel(const BandSystem& bands, const SolverOptions& options,
                              const SolveCallback& callback, std::vector<Rgb>& b,
                              SolveResult& result);
// Progressive refinement: shoots the patches with the most unshot power, in batches.
absl::Status SolveSouthwell(const BandSystem& bands, const SolverOptions& options,
                            const SolveCallback& callback, std::vector<Rgb>& b,
                            SolveResult& result);
// Conjugate gradient on the symmetric form (A / rho) B - sym(A F) B = (A / rho) E.
absl::Status SolveConjugateGradient(const BandSystem& bands, const SolverOptions& options,
                                    const SolveCallback& callback, std::vector<Rgb>& b,
                                    SolveResult& result);
// Dense LU with partial pivoting, double precision; n <= kMaxDirectPatches.
absl::Status SolveDirect(const BandSystem& bands, const SolverOptions& options,
                         const SolveCallback& callback, std::vector<Rgb>& b, SolveResult& result);

}  // namespace radflux
