#include "solver/sparse/csr_matrix.h"

#include <algorithm>
#include <cassert>

namespace radflux {

size_t CsrMatrix::Bytes() const {
  return row_begin.size() * sizeof(uint64_t) + col.size() * sizeof(uint32_t) +
         value.size() * sizeof(float);
}

double CsrMatrix::RowSum(uint32_t i) const {
  double sum = 0;
  for (float v : RowValues(i)) sum += v;
  return sum;
}

float CsrMatrix::At(uint32_t i, uint32_t j) const {
  const auto c = RowCols(i);
  const auto it = std::lower_bound(c.begin(), c.end(), j);
  if (it == c.end() || *it != j) return 0;
  return value[row_begin[i] + static_cast<uint64_t>(it - c.begin())];
}

void CsrMatrix::Reserve(uint32_t row_count, size_t nnz) {
  row_begin.reserve(row_count + 1);
  col.reserve(nnz);
  value.reserve(nnz);
}

void CsrMatrix::Append(const RowBlock& block) {
  assert(block.first_row == rows);
  const uint64_t base = col.size();
  col.insert(col.end(), block.col.begin(), block.col.end());
  value.insert(value.end(), block.value.begin(), block.value.end());
  for (size_t r = 1; r < block.row_begin.size(); ++r) row_begin.push_back(base + block.row_begin[r]);
  rows += block.RowCount();
}

}  // namespace radflux
