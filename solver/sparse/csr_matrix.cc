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

CsrMatrix CsrMatrix::Transposed() const {
  CsrMatrix t;
  t.rows = cols;
  t.cols = rows;
  t.row_begin.assign(static_cast<size_t>(cols) + 1, 0);
  for (uint32_t j : col) ++t.row_begin[j + 1];
  for (uint32_t j = 0; j < cols; ++j) t.row_begin[j + 1] += t.row_begin[j];
  t.col.resize(nnz());
  t.value.resize(nnz());
  std::vector<uint64_t> next(t.row_begin.begin(), t.row_begin.end() - 1);
  for (uint32_t i = 0; i < rows; ++i) {  // rows in order, so each column comes out ascending
    for (uint64_t e = row_begin[i]; e < row_begin[i + 1]; ++e) {
      const uint64_t slot = next[col[e]]++;
      t.col[slot] = i;
      t.value[slot] = value[e];
    }
  }
  return t;
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
