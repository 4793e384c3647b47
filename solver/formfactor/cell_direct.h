// Direct light per cell after a grouped solve (face_grouping.h). A group of patches is one
// unknown with one B, but the direct light on its patches can vary a lot within it (a wall
// beside a lamp, a ceiling above a lit screen). So the light is split in two levels: the
// solve's B_g carries the group's power, and each direct-light cell c of group g gets its
// own direct light by light sampling (LightSampler::CellEmitterColumns over the cell's
// patches, near-field rule included):
//     D_c = sum over emitter unknowns j of F_cj B_j              (W/m^2 per band)
// and each patch of cell c shows
//     B_p = B_g + rho_g (D_c - Dbar_g),   Dbar_g = sum over cells c of g of A_c D_c / A_g.
// The group's row took its emitter columns from these very samples (monte_carlo:
// LightSampler::AddGroupEmitterColumns, F_gj = sum_c A_c F_cj / A_g), so Dbar_g is the direct
// light the solve put into B_g (but for the float rows' rounding and a row the row-sum cap
// scaled back) and B_p = E_g + rho_g (D_c + I_g), I_g the group's irradiance from all but the
// emitters. The group's mean direct light is thus the cells' estimate (CellLightSamplesPerGroup,
// stratified over the cells), in the solve as well: the light the group reflects on carries
// it. The area-weighted mean of B over the group's patches is B_g exactly, so the power the
// solve balanced is the power the outputs show (for a group partly enclosed in a solid, over
// its exposed part: Dbar_g is then the exposed part's, exposed_area.h); only a patch whose B
// would fall below E_g is lifted to E_g (it cannot reflect negative light), which the
// summary counts.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/core/bands.h"
#include "solver/formfactor/form_factor_options.h"
#include "solver/formfactor/row_builder.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/patch_clusters.h"

namespace radflux {

struct CellDirectResult {
  std::vector<Rgb> radiosity;  // per patch of context.mesh, W/m^2 per band
  uint64_t cells = 0;          // cells sampled (those of groups with more than one cell)
  uint64_t kept = 0;           // of them, those whose columns the rows kept (cell_columns.h)
  uint64_t rays = 0;           // the shadow rays of the others
  uint64_t lifted = 0;         // patches lifted to E_g (see above)
  double seconds = 0;
};

// D_c of every cell and Dbar_g of every group, from `b` per unknown (the emitters' B): what
// the push-down shows, drawn as PushDownWithCellDirect draws it (context.cells set).
struct CellDirectLight {
  std::vector<uint32_t> group;   // per cell, its unknown
  std::vector<uint8_t> sampled;  // per cell, 1 where its group has more than one cell and a row
  std::vector<Rgb> direct;       // D_c per cell (0 where not sampled)
  std::vector<Rgb> mean;         // Dbar_g per unknown
  uint64_t cells = 0, kept = 0, rays = 0;  // as CellDirectResult's
};
CellDirectLight ComputeCellDirectLight(const RowContext& context, const std::vector<Rgb>& b,
                                       const FormFactorOptions& options);

// Per cell, what its patches show above their group's B: rho_g (D_c - Dbar_g) (0 where not
// sampled). Its area-weighted sum over a group's cells is 0.
std::vector<Rgb> CellDeviation(const CellDirectLight& light, const PatchAttributes& attributes);

// B per patch as above, from `b` per unknown of context (grouped: context.clusters and
// context.cells set) and `attributes` per unknown; each group's cells share a budget of
// CellLightSamplesPerGroup(options) light samples, seeded from options.seed: the cells'
// columns the rows kept in context.cell_columns for them, the others drawn here (the same
// numbers either way); on options.threads threads (the result does not depend on them). Unknowns of
// one cell, and those with rho = 0, show their B unchanged; without cells every patch shows its
// unknown's B. With `indirect` (per cell, cell_detail.h's CellDetail::indirect), each sampled
// cell's patches show that deviation of its reflected light too (its group's mean unchanged).
CellDirectResult PushDownWithCellDirect(const RowContext& context,
                                        const PatchAttributes& attributes,
                                        const std::vector<Rgb>& b, const FormFactorOptions& options,
                                        std::span<const Rgb> indirect = {});

}  // namespace radflux
