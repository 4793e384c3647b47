// SymmetricForm: S = sym(A F) with S_ij = (A_i F_ij + A_j F_ji) / 2, the symmetric
// off-diagonal part of the conjugate-gradient system, built once from the rows as CSR
// in double. Exactly symmetric by construction (both halves of a pair add the same two
// numbers). A pair stored on one side only (F_ij but no F_ji) counts as F_ji = 0 when
// row j holds any entries (e.g. a Monte Carlo row whose rays missed i), and as
// reciprocal (A_j F_ji = A_i F_ij) when row j is empty (a patch that needed no row).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/sparse/csr_matrix.h"

namespace radflux {

struct SymmetricForm {
  std::vector<uint64_t> row_begin{0};
  std::vector<uint32_t> col;  // strictly increasing within a row
  std::vector<double> value;  // S_ij, scene units^2
  // Over pairs i != j with both entries stored: max |A_iF_ij - A_jF_ji| / max(A_iF_ij, A_jF_ji).
  double reciprocity_error = 0;
  // Pairs i != j with only one entry stored while both rows are non-empty.
  int64_t one_sided_pairs = 0;
};

SymmetricForm BuildSymmetricForm(const CsrMatrix& f, const std::vector<double>& area);

}  // namespace radflux
