// The cells' detail as the other unknowns see it. A grouped solve gives a group one B, but
// its direct-light cells show B_g + delta_c, delta_c = rho_g (D_c - Dbar_g) (cell_direct.h).
// A receiver whose view of a group favours its bright cells (a ceiling above the lit seats
// of chairs whose legs and backs share their unknown) gets more than F_ig B_g from it:
//     H_i = sum over cells c of F_ic delta_c     (W/m^2 per band),
// which a row, one column per group, cannot hold. GatherCellDetail estimates H_i with cosine
// rays of its own from each unknown with a row (as many as its row casts, stratified, seeded
// apart from the row's), and the solve takes rho_i H_i as a known source beside E_i
// (pipeline: PushDownGroupedSolve). The estimate is unbiased for every delta; where the cells
// all see alike it is 0 in expectation, as sum_c A_c delta_c = 0 in every group.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/core/bands.h"
#include "solver/formfactor/form_factor_options.h"
#include "solver/formfactor/row_builder.h"

namespace radflux {

struct CellDetail {
  std::vector<Rgb> irradiance;  // H per unknown of the context, W/m^2 per band
  uint64_t rays = 0;            // the cosine rays cast
};

// H per unknown from `deviation` per cell of context.cells (which must be set), with
// options.rays, options.seed and options.threads (the result does not depend on the threads).
CellDetail GatherCellDetail(const RowContext& context, std::span<const Rgb> deviation,
                            const FormFactorOptions& options);

}  // namespace radflux
