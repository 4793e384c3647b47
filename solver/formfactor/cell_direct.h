// Direct light per cell after a grouped solve (face_grouping.h). A group of patches is one
// unknown with one B, but the direct light on its patches can vary a lot within it (a wall
// beside a lamp, a ceiling above a lit screen). So the light is split in two levels: the
// reflected light between groups is the solve's, and the direct light is each direct-light
// cell's own. Each cell c of group g gets, by the rows' light sampling (LightSampler over
// the cell's patches, near-field rule included),
//     D_c = sum over emitter unknowns j of F_cj B_j              (W/m^2 per band)
// (the rows of a group of more than one cell take their emitter columns from the same cell
// estimates, so the two levels agree) and each patch of cell c shows
//     B_p = B_g + rho_g (D_c - Dbar_g),   Dbar_g = sum over cells c of g of A_c D_c / A_g,
// that is E_g + rho_g (D_c + I_g) with I_g = (B_g - E_g) / rho_g - Dbar_g the group's
// irradiance from everything but the emitters (sum of F_gj B_j over non-emitter j, up to
// the rows' float storage). The area-weighted mean of B over the group's patches is B_g exactly, so
// the power the solve balanced is the power the outputs show; only a patch whose B would fall below
// E_g is lifted to E_g (it cannot reflect negative light), which the summary counts.
#pragma once

#include <cstdint>
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
  uint64_t rays = 0;           // shadow rays cast here: for the cells whose samples the rows
                               // did not leave in context.cell_columns
  uint64_t lifted = 0;         // patches lifted to E_g (see above)
  double seconds = 0;
};

// B per patch as above, from `b` per unknown of context (grouped: context.clusters and
// context.cells set), `attributes` per unknown, D_c from the samples the rows left in
// context.cell_columns, or else by LightSampler::AddCellEmitterColumns with options.samples
// points and options.seed (the same samples: the very estimates of the rows' emitter columns),
// on options.threads threads (the result does not depend on them). Unknowns of one cell, and
// those with rho = 0, show their B unchanged; without cells every patch shows its unknown's B.
CellDirectResult PushDownWithCellDirect(const RowContext& context,
                                        const PatchAttributes& attributes,
                                        const std::vector<Rgb>& b,
                                        const FormFactorOptions& options);

}  // namespace radflux
