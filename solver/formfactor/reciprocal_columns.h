// ReciprocalColumns: the entries of every row towards the hidden unknowns (slots,
// contact_footprints.h), taken from the hidden unknowns' own rows by reciprocity.
//
// A slot is a strip of a face under an emitter facing it, often far brighter than anything
// else (the corridor's ceiling 2 cm above each lamp's top), seen from the room only through
// the slit around the emitter. The room's cosine rays rarely pass a 2 cm slit, and each that
// does carries the strip's whole B: the room's gather from a slot is heavy-tailed (the
// corridor's energy balance swung -454..+208 W over seeds). The slot's own rays leave through
// the slit as often as it is open. So the hidden unknowns' rows are built first, and every
// other row i takes, for each hidden unknown j with less area per ray than i
// (ReadFromHiddenRow, row_rays.h: the wall, not the small part one strip ray would light
// whole), A_j F_ji / A_i (A the opaque areas) instead of its own hits on j: by reciprocity
// (A_i F_ij = A_j F_ji) an unbiased estimate of F_ij when F_ji is one, and the pair then
// exchanges power exactly both ways, so it adds nothing to the energy balance's imbalance
// (EnergyBalance: RowSampling::reciprocal). Hidden unknowns that are emitters or have no row,
// and the pairs of two hidden unknowns, keep the rows' own hits.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "solver/formfactor/row_builder.h"

namespace radflux {

class ReciprocalColumns {
 public:
  // Builds one row into an empty accumulator; returns the rays it cast.
  using BuildRow = std::function<uint64_t(uint32_t, RowAccumulator&)>;

  ReciprocalColumns() = default;
  // Builds the row of every hidden unknown with a row that does not emit with `build` (in
  // parallel on `threads` threads, 0 = all cores; each row depends only on its index) and
  // keeps them and their transpose; the rows cast `rays` (--rays) as RowRayCount says.
  ReciprocalColumns(const RowContext& context, int rays, int threads, const BuildRow& build);

  // Whether row j is such a hidden unknown's.
  bool Hidden(uint32_t j) const { return j < filled_.size() && filled_[j] != 0; }
  // Whether row i's entry in column j comes from row j.
  bool Fills(uint32_t i, uint32_t j) const;
  // Adds the row of hidden unknown j, as built (with what its cap removed), to `row`;
  // returns the rays it cast.
  uint64_t AddOwnRow(uint32_t j, RowAccumulator& row) const;
  // Adds A_j F_ji / A_i to column j of `row` for every hidden unknown j whose row reaches i.
  void AddColumns(uint32_t i, RowAccumulator& row) const;

 private:
  std::vector<uint8_t> filled_;  // per unknown: Hidden(j)
  const RowContext* context_ = nullptr;
  int rays_ = 0;
  // The rows of the filled unknowns: entries rows_entries_[rows_first_[r], rows_first_[r+1])
  // of the filled unknown rows_of_[r], and its rays.
  std::vector<uint32_t> rows_of_;
  std::vector<uint64_t> row_rays_;
  std::vector<double> row_scaled_off_;  // what the row-sum cap removed from each
  std::vector<uint32_t> rows_first_;
  std::vector<std::pair<uint32_t, double>> rows_entries_;
  std::vector<uint32_t> row_index_;  // per unknown: its index r in rows_of_ (when filled)
  // The transpose: per unknown i, (j, A_j F_ji / A_i) in
  // columns_entries_[columns_first_[i], columns_first_[i + 1]).
  std::vector<uint32_t> columns_first_;
  std::vector<std::pair<uint32_t, double>> columns_entries_;
};

// Per unknown, 1 where ReciprocalColumns fills the other rows' entries towards it (the
// monte_carlo rows of `options`, those of rows with more area per ray; all 0 for the other
// methods): the energy balance's RowSampling::reciprocal.
std::vector<uint8_t> ReciprocallyFilled(const RowContext& context,
                                        const FormFactorOptions& options);

}  // namespace radflux
