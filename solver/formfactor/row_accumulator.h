// RowAccumulator: dense scratch for one row with a list of touched columns, so that
// clearing costs the row's non-zeros, not n. One per thread.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "solver/sparse/csr_matrix.h"

namespace radflux {

class RowAccumulator {
 public:
  explicit RowAccumulator(size_t n) : value_(n, 0.0) {}

  // Adds v > 0 to column j (non-positive v is ignored).
  void Add(uint32_t j, double v) {
    if (!(v > 0)) return;
    if (value_[j] == 0) touched_.push_back(j);
    value_[j] += v;
  }

  // The row so far (read-only; for checks that need the double values before Flush).
  double Value(uint32_t j) const { return value_[j]; }
  const std::vector<uint32_t>& Touched() const { return touched_; }

  // Moves the row into `block` (ascending columns, entries >= cutoff) and clears it;
  // returns the sum of the entries the cut-off dropped.
  double Flush(double cutoff, RowBlock& block) {
    std::sort(touched_.begin(), touched_.end());
    double dropped = 0;
    for (uint32_t j : touched_) {
      const double v = value_[j];
      value_[j] = 0;
      if (v >= cutoff) {
        block.Add(j, static_cast<float>(v));
      } else {
        dropped += v;
      }
    }
    touched_.clear();
    block.EndRow();
    return dropped;
  }

 private:
  std::vector<double> value_;
  std::vector<uint32_t> touched_;
};

}  // namespace radflux
