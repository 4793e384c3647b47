// Reciprocity averaging of Monte Carlo rows: every cosine ray between two patches counts for
// both directions of the pair.
//
// Row i estimates F_ij from its own k_i cosine rays, h_ij / k_i (h_ij of them meet j), and
// row j estimates the same F_ij by reciprocity (A_i F_ij = A_j F_ji), h_ji / (A_i d_j), with
// d = k / A a row's rays per unit area. Both are unbiased, with (binomial) variances
// F_ij / k_i and F_ij / (A_i d_j); weighted by their inverses they make
//     F_ij = (h_ij + h_ji) / (A_i (d_i + d_j)),
// half the variance of either when the two rows have the same rays per area (as the rows'
// area-proportional rays give them, row_rays.h). Each row's averaged entries are then scaled
// to the sum its own rays gave them: a row's sum stays one multinomial draw of its own rays,
// so a closed room's rows still sum to 1 exactly (its B stays exact whatever the noise) and
// no row passes its cap (RowContext::MaxRowSum), while the averaged pairs keep the lower
// variance of how the sum is shared out. Without that scaling a pair's two entries vary
// together (the same hits), which biases B up by the round trip i -> j -> i: +0.1-0.16% on the
// Cornell box's surfaces at k = 64, and the row sums' own noise broke high-rho closed rooms.
//
// Only pairs of two cosine-ray rows take part: not an emitter's or a bright reflector's column
// (light sampled: light_sampling.h, bright_reflectors.h) nor their rows, not rows of patches
// without a row (rho = 0), not the diagonal (a group's F_ii). Columns towards hidden unknowns
// that come from their rows already (reciprocal_columns.h) are reciprocal and stay as they are
// but for the scaling.
#pragma once

#include <cstdint>
#include <span>

#include "solver/formfactor/row_builder.h"

namespace radflux {

// Averages the pairs of `rows` (all rows of `context`, each built with RowRayCount(rays, ...)
// cosine rays, row_rays.h) whose unknowns both have cosine[u] != 0, as above; runs on
// `threads` threads (0 = all cores).
void AverageReciprocalPairs(const RowContext& context, int rays, std::span<const uint8_t> cosine,
                            int threads, CsrMatrix& rows);

}  // namespace radflux
