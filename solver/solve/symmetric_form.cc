#include "solver/solve/symmetric_form.h"

#include <algorithm>
#include <cmath>

namespace radflux {
namespace {

// F^T with entries A_j F_ji in row i, columns j increasing.
void Transpose(const CsrMatrix& f, const std::vector<double>& area, std::vector<uint64_t>& begin,
               std::vector<uint32_t>& col, std::vector<double>& value) {
  const uint32_t n = f.rows;
  begin.assign(n + 1, 0);
  for (uint32_t c : f.col) ++begin[c + 1];
  for (uint32_t i = 0; i < n; ++i) begin[i + 1] += begin[i];
  col.resize(f.nnz());
  value.resize(f.nnz());
  std::vector<uint64_t> next(begin.begin(), begin.end() - 1);
  for (uint32_t j = 0; j < n; ++j) {
    const auto cols = f.RowCols(j);
    const auto values = f.RowValues(j);
    for (size_t e = 0; e < cols.size(); ++e) {
      const uint64_t at = next[cols[e]]++;
      col[at] = j;
      value[at] = area[j] * values[e];
    }
  }
}

bool RowEmpty(const CsrMatrix& f, uint32_t i) { return f.row_begin[i] == f.row_begin[i + 1]; }

}  // namespace

SymmetricForm BuildSymmetricForm(const CsrMatrix& f, const std::vector<double>& area) {
  std::vector<uint64_t> t_begin;
  std::vector<uint32_t> t_col;
  std::vector<double> t_value;
  Transpose(f, area, t_begin, t_col, t_value);
  SymmetricForm s;
  s.row_begin.reserve(f.rows + 1);
  for (uint32_t i = 0; i < f.rows; ++i) {
    const auto cols = f.RowCols(i);
    const auto values = f.RowValues(i);
    size_t a = 0;
    uint64_t b = t_begin[i];
    while (a < cols.size() || b < t_begin[i + 1]) {
      const uint32_t ja = a < cols.size() ? cols[a] : f.rows;
      const uint32_t jb = b < t_begin[i + 1] ? t_col[b] : f.rows;
      const uint32_t j = std::min(ja, jb);
      const double forward = ja == j ? area[i] * values[a++] : 0;  // A_i F_ij
      const double reverse = jb == j ? t_value[b++] : 0;           // A_j F_ji
      double sij = 0.5 * (forward + reverse);
      if (forward == 0 && RowEmpty(f, i)) sij = reverse;
      if (reverse == 0 && RowEmpty(f, j)) sij = forward;
      if (j != i && forward > 0 && reverse > 0) {
        s.reciprocity_error =
            std::max(s.reciprocity_error, std::abs(forward - reverse) / std::max(forward, reverse));
      } else if (j != i && ja == j && jb != j && !RowEmpty(f, j)) {
        ++s.one_sided_pairs;  // counted once, from the row that holds the entry
      }
      s.col.push_back(j);
      s.value.push_back(sij);
    }
    s.row_begin.push_back(s.col.size());
  }
  return s;
}

}  // namespace radflux
