// CsrMatrix: compressed sparse rows of form factors F_ij (column index + float value).
// Rows are complete and in order; columns within a row are strictly increasing.
// A row may be empty (a patch that needs no row, rho = 0).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace radflux {

// Consecutive rows [first_row, EndRow()) in CSR layout, not owned: row i's entries are
// col/value[row_begin[i - first_row], row_begin[i - first_row + 1]). What solvers that
// stream rows see, whether the rows are one CsrMatrix or a block read back from disk.
struct RowsView {
  uint32_t first_row = 0;
  std::span<const uint64_t> row_begin;  // RowCount() + 1 offsets into col/value
  const uint32_t* col = nullptr;
  const float* value = nullptr;

  uint32_t RowCount() const { return static_cast<uint32_t>(row_begin.size() - 1); }
  uint32_t EndRow() const { return first_row + RowCount(); }
  std::span<const uint32_t> RowCols(uint32_t i) const {
    return {col + row_begin[i - first_row], col + row_begin[i - first_row + 1]};
  }
  std::span<const float> RowValues(uint32_t i) const {
    return {value + row_begin[i - first_row], value + row_begin[i - first_row + 1]};
  }
};

// One block of consecutive rows built independently (by a thread or a worker).
struct RowBlock {
  uint32_t first_row = 0;
  std::vector<uint64_t> row_begin{0};  // size = rows in block + 1, offsets into col/value
  std::vector<uint32_t> col;
  std::vector<float> value;

  uint32_t RowCount() const { return static_cast<uint32_t>(row_begin.size() - 1); }
  void Add(uint32_t column, float v) {
    col.push_back(column);
    value.push_back(v);
  }
  void EndRow() { row_begin.push_back(col.size()); }
  size_t Bytes() const {
    return row_begin.size() * sizeof(uint64_t) + col.size() * sizeof(uint32_t) +
           value.size() * sizeof(float);
  }
  RowsView View() const { return {first_row, row_begin, col.data(), value.data()}; }
};

struct CsrMatrix {
  uint32_t rows = 0;
  uint32_t cols = 0;
  std::vector<uint64_t> row_begin{0};
  std::vector<uint32_t> col;
  std::vector<float> value;

  size_t nnz() const { return col.size(); }
  // Bytes held by the three arrays.
  size_t Bytes() const;
  std::span<const uint32_t> RowCols(uint32_t i) const {
    return {col.data() + row_begin[i], col.data() + row_begin[i + 1]};
  }
  std::span<const float> RowValues(uint32_t i) const {
    return {value.data() + row_begin[i], value.data() + row_begin[i + 1]};
  }
  double RowSum(uint32_t i) const;
  RowsView View() const { return {0, row_begin, col.data(), value.data()}; }
  // F_ij, or 0 when absent (binary search in row i).
  float At(uint32_t i, uint32_t j) const;
  // F^T: row j of the result holds column j of this matrix (cols x rows), columns ascending.
  CsrMatrix Transposed() const;
  // Makes room for `rows` rows with `nnz` entries in all, so appending does not reallocate.
  void Reserve(uint32_t rows, size_t nnz);
  // Appends a block; its first_row must equal `rows` (blocks arrive in order).
  void Append(const RowBlock& block);
};

}  // namespace radflux
