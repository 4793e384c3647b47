// The part of a solution's radiosity that did not come straight from an emitter's emission:
// what the picture interpolates between patches while it samples the direct light at every
// pixel (output/final_gather.h), for the patches it does not gather afresh
// (output/indirect_regather.h). With the solve's rows F and B,
//     I_i = B_i - E_i - rho_i * sum over emitters j (E_j > 0) of F_ij E_j,
// which at convergence is rho_i times the irradiance from everything but emission (an
// emitter's own reflection included, plus any source the solve added beside E, such as the
// cells' detail): light that has bounced at least once. It varies far more slowly over a
// surface than the direct light, so Gouraud shading shows it well on patches too coarse for
// shadows and the falloff under a lamp.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/solve/solver.h"

namespace radflux {

// I per unknown of `system` (clamped at 0) from its solution `b`; an unknown without a row
// (rho = 0) gets 0. INVALID_ARGUMENT when b's size is not the system's; the row store's read
// error when spilled rows cannot be read.
absl::StatusOr<std::vector<Rgb>> ReflectedIndirect(const RadiositySystem& system,
                                                   const std::vector<Rgb>& b);

}  // namespace radflux
