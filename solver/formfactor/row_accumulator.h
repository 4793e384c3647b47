// RowAccumulator: dense scratch for one row with a list of touched columns, so that
// clearing costs the row's non-zeros, not n. One per thread.
// A bitmap of the touched columns gives them in ascending order by a scan of n/64 words
// when the row is dense enough for that to beat sorting them.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "solver/sparse/csr_matrix.h"

namespace radflux {

// A row the row-sum cap scaled back (RowAccumulator::CapSum): the row and the sum of its form
// factors the cap removed (A_i B_i times it is the power removed, W per band).
struct ScaledRow {
  uint32_t row = 0;
  double removed = 0;
};

class RowAccumulator {
 public:
  explicit RowAccumulator(size_t n) : value_(n, 0.0), marked_((n + 63) / 64, 0) {}

  // Adds v > 0 to column j (non-positive v is ignored).
  void Add(uint32_t j, double v) {
    if (!(v > 0)) return;
    if (value_[j] == 0) {
      touched_.push_back(j);
      marked_[j / 64] |= uint64_t{1} << (j % 64);
    }
    value_[j] += v;
  }

  // Multiplies every entry of the row so far by factor > 0.
  void Scale(double factor) {
    for (uint32_t j : touched_) value_[j] *= factor;
  }

  // Scales the row back to sum `limit` when its entries sum to more; the sum it removed is
  // ScaledOff() until the next Flush or Clear.
  void CapSum(double limit) {
    double sum = 0;
    for (uint32_t j : touched_) sum += value_[j];
    if (!(sum > limit)) return;
    Scale(limit / sum);
    scaled_off_ += sum - limit;
  }
  double ScaledOff() const { return scaled_off_; }
  // Books `removed` as scaled off (a capped row added back from a copy: reciprocal_columns).
  void AddScaledOff(double removed) { scaled_off_ += removed; }

  // The row so far (read-only; for checks that need the double values before Flush).
  double Value(uint32_t j) const { return value_[j]; }
  const std::vector<uint32_t>& Touched() const { return touched_; }

  // Empties the row (for a caller that reads it with Value and Touched and keeps no block).
  void Clear() {
    scaled_off_ = 0;
    for (uint32_t j : touched_) {
      value_[j] = 0;
      marked_[j / 64] = 0;
    }
    touched_.clear();
  }

  // Moves the row into `block` (ascending columns, entries >= cutoff, and every entry in
  // a column with keep[j] != 0: emitter columns, which carry direct light however small
  // the form factor) and clears it; returns the sum of the entries the cut-off dropped.
  double Flush(double cutoff, RowBlock& block, const std::vector<uint8_t>* keep = nullptr) {
    SortTouched();
    scaled_off_ = 0;
    double dropped = 0;
    for (uint32_t j : touched_) {
      const double v = value_[j];
      value_[j] = 0;
      if (v >= cutoff || (keep != nullptr && j < keep->size() && (*keep)[j] != 0)) {
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
  // Puts touched_ in ascending order and clears marked_.
  void SortTouched() {
    if (touched_.size() * 16 < marked_.size()) {  // sparse: sort and clear the marked words
      std::sort(touched_.begin(), touched_.end());
      for (uint32_t j : touched_) marked_[j / 64] = 0;
      return;
    }
    touched_.clear();
    for (size_t w = 0; w < marked_.size(); ++w) {
      for (uint64_t bits = marked_[w]; bits != 0; bits &= bits - 1) {
        touched_.push_back(
            static_cast<uint32_t>(64 * w + static_cast<size_t>(std::countr_zero(bits))));
      }
      marked_[w] = 0;
    }
  }

  std::vector<double> value_;
  std::vector<uint32_t> touched_;
  std::vector<uint64_t> marked_;  // bit j set when column j is in touched_
  double scaled_off_ = 0;         // the row sum CapSum removed
};

}  // namespace radflux
