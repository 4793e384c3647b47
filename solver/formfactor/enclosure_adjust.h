// View3D's enclosure adjustment (encl=1; NormAF in View3D's viewpp.c): in a closed
// enclosure every row sums to 1 and A_i F_ij = A_j F_ji. The matrix AF_ij = A_i F_ij is made
// symmetric (the mean of the two directions), then each surface's row and column of AF are
// scaled together by 1 / sum_j F_ij, sweep after sweep, until every row sum is within
// `tolerance` of 1: reciprocity stays exact and closure is reached. View3D's own tolerance is
// 1e-7 with at most 100 sweeps.
#pragma once

#include <vector>

namespace radflux {

// How far a view-factor matrix is from closure and reciprocity.
struct EnclosureError {
  double max_closure = 0;      // max_i |1 - sum_j F_ij|
  double rms_closure = 0;      // RMS over i of 1 - sum_j F_ij
  double max_reciprocity = 0;  // max_ij |A_i F_ij - A_j F_ji| / max(A_i F_ij, A_j F_ji)
};

EnclosureError MeasureEnclosureError(const std::vector<std::vector<double>>& factor,
                                     const std::vector<double>& area);

struct EnclosureAdjustment {
  EnclosureError before, after;
  int sweeps = 0;
  bool converged = false;  // every row sum within tolerance after `sweeps`
};

// Adjusts `factor` (factor[i][j] = F_ij, square, areas in m^2) in place as stated above.
// A row that sees nothing (sum 0) is left as it is.
EnclosureAdjustment AdjustEnclosure(std::vector<std::vector<double>>& factor,
                                    const std::vector<double>& area, double tolerance = 1e-7,
                                    int max_sweeps = 100);

}  // namespace radflux
