// The error left in a solution B of B = E + rho F B, estimated from its residual.
#pragma once

#include <vector>

#include "absl/status/status.h"
#include "solver/solve/band_system.h"
#include "solver/solve/solver.h"

namespace radflux {

// Sets result.error_estimate and result.error_estimate_method for the lane values `b` with
// residual `r` (E + rho F B - B). With q = max_i rho_i sum_j F_ij < 1 the rows are a
// contraction in the max norm, so |B* - B|_inf <= |r|_inf / (1 - q) ("bound"); otherwise
// the last iterations' contraction rate c of result.residual_history gives
// residual / (1 - c) ("rate"; none when they did not contract). Both are relative to
// max_i |B_i - E_i|, the reflected part, max over lanes. Fails only on a row store read.
absl::Status EstimateError(const BandSystem& bands, const std::vector<Rgb>& b,
                           const std::vector<Rgb>& r, SolveResult& result);

}  // namespace radflux
