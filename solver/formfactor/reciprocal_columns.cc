#include "solver/formfactor/reciprocal_columns.h"

#include <algorithm>

#include "solver/core/parallel.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

// Whether unknown u is a hidden patch with a row that does not emit.
bool Filled(const RowContext& context, uint32_t u) {
  return context.needs_row[u] && !context.emitter[u] && context.SinglePatch(u) &&
         context.mesh->patches[context.FirstPatch(u)].hidden;
}

}  // namespace

ReciprocalColumns::ReciprocalColumns(const RowContext& context, int rays, int threads,
                                     const BuildRow& build)
    : context_(&context), rays_(rays) {
  const uint32_t n = context.Unknowns();
  filled_.assign(n, 0);
  row_index_.assign(n, 0);
  for (uint32_t u = 0; u < n; ++u) {
    if (!Filled(context, u)) continue;
    filled_[u] = 1;
    row_index_[u] = static_cast<uint32_t>(rows_of_.size());
    rows_of_.push_back(u);
  }
  if (rows_of_.empty()) return;
  std::vector<std::vector<std::pair<uint32_t, double>>> rows(rows_of_.size());
  row_rays_.assign(rows_of_.size(), 0);
  row_scaled_off_.assign(rows_of_.size(), 0);
  ParallelFor(static_cast<int64_t>(rows_of_.size()), 4, threads, [&](int64_t begin, int64_t end) {
    RowAccumulator row(n);
    for (int64_t r = begin; r < end; ++r) {
      row_rays_[r] = build(rows_of_[r], row);
      row_scaled_off_[r] = row.ScaledOff();
      for (uint32_t i : row.Touched()) rows[r].emplace_back(i, row.Value(i));
      row.Clear();
    }
  });
  rows_first_.push_back(0);
  std::vector<uint32_t> count(n + 1, 0);
  for (size_t r = 0; r < rows.size(); ++r) {
    for (const auto& [i, f] : rows[r]) {
      rows_entries_.emplace_back(i, f);
      if (Fills(i, rows_of_[r])) ++count[i + 1];
    }
    rows_first_.push_back(static_cast<uint32_t>(rows_entries_.size()));
  }
  columns_first_.assign(n + 1, 0);
  for (uint32_t i = 0; i < n; ++i) columns_first_[i + 1] = columns_first_[i] + count[i + 1];
  columns_entries_.resize(columns_first_[n]);
  std::vector<uint32_t> next(columns_first_.begin(), columns_first_.end() - 1);
  for (size_t r = 0; r < rows.size(); ++r) {  // in row order: each column's j ascend
    const uint32_t j = rows_of_[r];
    for (const auto& [i, f] : rows[r]) {
      if (!Fills(i, j)) continue;
      columns_entries_[next[i]++] = {j, context.opaque_area[j] * f / context.opaque_area[i]};
    }
  }
}

bool ReciprocalColumns::Fills(uint32_t i, uint32_t j) const {
  return Hidden(j) && !Hidden(i) &&
         ReadFromHiddenRow(rays_, context_->opaque_area[i], context_->Emits(i),
                           context_->opaque_area[j], context_->mean_row_area);
}

uint64_t ReciprocalColumns::AddOwnRow(uint32_t j, RowAccumulator& row) const {
  const uint32_t r = row_index_[j];
  for (uint32_t e = rows_first_[r]; e < rows_first_[r + 1]; ++e) {
    row.Add(rows_entries_[e].first, rows_entries_[e].second);
  }
  row.AddScaledOff(row_scaled_off_[r]);
  return row_rays_[r];
}

void ReciprocalColumns::AddColumns(uint32_t i, RowAccumulator& row) const {
  if (columns_first_.empty()) return;
  for (uint32_t e = columns_first_[i]; e < columns_first_[i + 1]; ++e) {
    row.Add(columns_entries_[e].first, columns_entries_[e].second);
  }
}

std::vector<uint8_t> ReciprocallyFilled(const RowContext& context,
                                        const FormFactorOptions& options) {
  const uint32_t n = context.Unknowns();
  std::vector<uint8_t> filled(n, 0);
  if (options.method != FormFactorMethod::kMonteCarlo) return filled;
  for (uint32_t u = 0; u < n; ++u) filled[u] = Filled(context, u) ? 1 : 0;
  return filled;
}

}  // namespace radflux
