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
// without a row (rho = 0), not the diagonal (a group's F_ii), not a hidden unknown's (its
// pairs are exactly reciprocal already: reciprocal_columns.h).
//
// The rows may be in memory or in a RowStore that spills (row_store.h): both give the same
// averaged rows, bit for bit. Row i needs column i of the others (h_ji). Rows in memory gather
// them in one pass. Stored rows are averaged in ranges of rows whose own rows and back hits fit
// the working memory given, with bounded IO whatever the number of ranges: one pass counts
// each row's entries and back hits; if there is more than one range, one pass writes each
// back hit (i, j, h_ji) to its range's bucket (entry_buckets.h, 12 bytes a hit); one last pass
// copies each range's own rows and, at the range's end, reads its bucket and averages it. So
// the store's spilled chunks are read 3 times (2 with one range), and the buckets are written
// and read once: 12 bytes per back hit <= 12 per stored entry <= 1.5 x the store's bytes.
// Total reads <= 3 x SpilledBytes() + 1.5 x Bytes() (ReciprocalPairs.SpilledIoIsBounded).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "solver/formfactor/row_builder.h"
#include "solver/sparse/row_store.h"

namespace radflux {

// What averaging stored rows took (ReciprocalPairs::Average).
struct SpilledAveraging {
  int ranges = 0;                     // ranges averaged one at a time
  uint64_t bucket_bytes_written = 0;  // back hits written to the bucket file
  uint64_t bucket_bytes_read = 0;     // ... and read back
};

class ReciprocalPairs {
 public:
  // The pairs of `context`'s rows (each built with RowRayCount(rays, ...) cosine rays,
  // row_rays.h) whose unknowns both have cosine[u] != 0.
  ReciprocalPairs(const RowContext& context, int rays, std::span<const uint8_t> cosine);

  // Rows in memory, averaged in place, on `threads` threads (0 = all cores).
  void Average(int threads, CsrMatrix& rows) const;
  // The rows of `rows` averaged and appended to `out` (empty, same columns), which is then
  // finished. Ranges of rows whose own rows and back hits take at most `working_bytes` (one
  // row at least) are averaged at a time; with more than one range, the back hits go to a
  // bucket file in `directory` ("" = a fresh one under $TMPDIR, as FileBlockSpill). Returns a
  // store's or the buckets' error (disk full, IO); `out` is then not to be used.
  absl::StatusOr<SpilledAveraging> Average(int threads, const RowStore& rows,
                                           uint64_t working_bytes, const std::string& directory,
                                           RowStore& out) const;

 private:
  class RangeHits;
  // One pass over the rows (in memory or in the store): per row, own[i] its entries and
  // back[i] the other rows' entries that average with its own.
  absl::Status Count(const CsrMatrix* matrix, const RowStore* store, std::vector<uint32_t>& own,
                     std::vector<uint32_t>& back) const;
  // The back hits on hits' rows from rows `rows`.
  void Gather(const RowsView& rows, RangeHits& hits) const;
  // Rows [hits.first, hits.last) of `own` averaged, in blocks in row order.
  std::vector<RowBlock> AverageRows(int threads, const RowsView& own, const RangeHits& hits) const;

  std::vector<double> area_, rays_, density_;  // per unknown: A, k, k / A (0: takes no part)
  // Per unknown, RowContext::Exposure: a row built scaled by 1 / exposure is read back as
  // its hits (Hits), the pair's two estimates of A_i F_ij of the whole area.
  std::vector<double> exposure_;
  // The cosine hits behind entry `value` of row i: k_i F_ij exposure_i.
  double Hits(uint32_t i, double value) const { return rays_[i] * exposure_[i] * value; }
  std::vector<uint8_t> takes_part_;
};

}  // namespace radflux
