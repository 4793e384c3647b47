// Bright reflectors: unknowns that do not emit but whose direct light makes them light sources
// for the rest of the scene (a lamp housing's inside, a few cm from its tube, shows ~100 times
// the room's mean radiosity and sends out ~20% of the room's light). A cosine ray meets such a
// small, bright patch seldom, and each hit is worth B_j / k: at k = 64 one hit on office2's
// housing adds +80% to a light switch's B, so small receivers' errors are heavy-tailed
// (+152% on one seed, -11% on another). monte_carlo rows therefore estimate their columns as
// they do an emitter's: by light sampling (light_sampling.h), with the rows' cosine hits on
// them weighted by multiple importance sampling or dropped. Any column's estimate may come
// from either sampler (each is an unbiased form-factor estimate from the geometry alone), so
// the rows stay unbiased; the estimated B below only steers the light tree's choice
// (importance), and the row's light-sample budget is shared with the emitters.
#pragma once

#include "solver/formfactor/row_builder.h"

namespace radflux {

// A single-patch unknown that neither emits nor is hidden (a slot, whose columns come from
// its own row by reciprocity) is a bright reflector when rho_u H_u, H_u its unoccluded
// irradiance from the emitters at its centroid, exceeds kBrightReflector times the scene's
// emitted power per unit area (the mean radiosity the first bounce would give it).
inline constexpr double kBrightReflector = 16;
// ... and when it sends out at least this fraction of the emitted power, rho_u H_u A_u: a
// sliver of a housing (1e-4 m^2) is met so seldom that it adds nothing but cost to the light
// tree (each light sample's cut weighs every emitter near it).
inline constexpr double kBrightReflectorPower = 1e-3;

// `context` with its bright reflectors marked as emitter columns (RowContext::emitter) of
// importance rho_u H_u (RowContext::emission); their emission in the scene stays zero. The
// same context when nothing emits.
RowContext WithBrightReflectors(const RowContext& context);

}  // namespace radflux
