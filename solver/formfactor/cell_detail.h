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
//
// The light a group reflects from the rest of the room varies across it as its direct light
// does, mostly from face to face (a desk's top under the bright ceiling, its underside over
// the dark floor), and a flat B_g sends the hidden faces' share into the clutter and shows the
// walls too little of the open ones: RenderPark's classroom at 2,000 unknowns read 1.7% dark
// against Cycles (by --gather 32), 0.6% at 8,000. So, given the solve's B, the same rays (cast
// once and kept: no extra rays) also read the irradiance of each of the group's faces from the
// non-emitting unknowns, I_f: the mean over the rays that start on f of B_j plus the direct
// detail of the cell they meet; a ray that meets a back side left a part enclosed in a solid,
// whose light no one sees, and does not count (B_g is the exposed part's). delta_c takes
// rho_g (I_c - Ibar_g) besides, I_c the area-weighted mean of I_f over the cell's patches (a
// face without a counted ray reads Ibar_g), Ibar_g the mean over the group's read patches:
// still 0 over the group. Per face, not per cell: a cell casts one or two of its group's rays,
// and per cell the noise showed in the groups' B (a back wall swung -10..+13% by seed). The
// push-down shows this part too (cell_direct.h), so pictures and per-patch values see it.
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
  uint64_t indirect_cells = 0;  // cells whose delta took their own indirect light (I_c)
  std::vector<Rgb> indirect;    // per cell, that part of delta: rho_g (I_c - Ibar_g) (empty
                                // without the solve's light)
};

// The solve's light for the cells' indirect detail: B and rho (per band) per unknown.
struct SolvedLight {
  std::span<const Rgb> radiosity;
  std::span<const Rgb> reflectance;
};

// H per unknown from `deviation` per cell of context.cells (which must be set), with
// options.rays, options.seed and options.threads (the result does not depend on the threads);
// with `solved`, the cells of groups of more than one cell also take their indirect
// deviation (above).
CellDetail GatherCellDetail(const RowContext& context, std::span<const Rgb> deviation,
                            const FormFactorOptions& options, const SolvedLight* solved = nullptr);

}  // namespace radflux
