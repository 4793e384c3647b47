#include "solver/formfactor/row_builder.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>

#include "solver/core/parallel.h"
#include "solver/core/seconds_since.h"
#include "solver/formfactor/builders.h"
#include "solver/formfactor/reciprocal_pairs.h"
#include "solver/sparse/file_block_spill.h"
#include "solver/sparse/ordered_row_appender.h"

namespace radflux {

void RowBlockStats::Merge(const RowBlockStats& o) {
  rays += o.rays;
  dropped_sum += o.dropped_sum;
  max_row_dropped = std::max(max_row_dropped, o.max_row_dropped);
  dropped_area += o.dropped_area;
  scaled_off.insert(scaled_off.end(), o.scaled_off.begin(), o.scaled_off.end());
}

std::unique_ptr<RowBuilder> MakeRowBuilder(const RowContext& context,
                                           const FormFactorOptions& options) {
  switch (options.method) {
    case FormFactorMethod::kMonteCarlo:
      return MakeMonteCarloBuilder(context, options);
    case FormFactorMethod::kHemicube:
      return MakeHemicubeBuilder(context, options);
    case FormFactorMethod::kAnalytic:
      return MakeAnalyticBuilder(context, options);
  }
  return nullptr;
}

RowBlock BuildRowBlock(const RowBuilder& builder, const RowContext& context, double cutoff,
                       uint32_t first, uint32_t count, RowAccumulator& row, RowBlockStats& stats) {
  RowBlock block;
  block.first_row = first;
  block.row_begin.reserve(count + 1);
  for (uint32_t i = first; i < first + count; ++i) {
    if (context.needs_row[i]) stats.rays += builder.BuildRow(i, row);
    if (row.ScaledOff() > 0) stats.scaled_off.push_back({i, row.ScaledOff()});
    const double dropped = row.Flush(cutoff, block, &context.emitter);
    stats.dropped_sum += dropped;
    stats.dropped_area += context.Area(i) * dropped;
    stats.max_row_dropped = std::max(stats.max_row_dropped, dropped);
  }
  return block;
}

double RayEpsilonFor(const PatchMesh& mesh) {
  double largest = 0;
  for (const Vec3& p : mesh.positions) {
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  return kRayLiftUlps * std::numeric_limits<float>::epsilon() * largest;
}

namespace {

// Builds every block of rows in parallel and hands each to deliver(index, block) as soon as
// it is done (on any thread, in any order). Stops early and returns the error when deliver
// fails, CANCELLED when progress returns false.
absl::StatusOr<RowBlockStats> BuildBlocks(
    const RowBuilder& builder, const RowContext& context, const FormFactorOptions& options,
    const PhaseProgress& progress, const std::function<absl::Status(uint32_t, RowBlock)>& deliver) {
  const uint32_t n = context.Unknowns();
  const uint32_t block_size = static_cast<uint32_t>(std::max(1, options.block_size));
  const uint32_t block_count = (n + block_size - 1) / block_size;

  std::vector<RowBlockStats> block_stats(block_count);
  const int threads = ThreadCount(options.threads);
  std::vector<std::unique_ptr<RowAccumulator>> scratch(static_cast<size_t>(threads));
  std::atomic<int64_t> rows_done{0};
  std::atomic<bool> cancelled{false};
  std::mutex error_mutex;
  absl::Status error;

  ParallelFor(block_count, 1, threads, [&](int64_t begin, int64_t end) {
    auto& row = scratch[static_cast<size_t>(ThreadIndex())];
    if (!row) row = std::make_unique<RowAccumulator>(n);
    for (int64_t b = begin; b < end && !cancelled.load(std::memory_order_relaxed); ++b) {
      const uint32_t first = static_cast<uint32_t>(b) * block_size;
      const uint32_t count = std::min(block_size, n - first);
      absl::Status s = deliver(
          static_cast<uint32_t>(b),
          BuildRowBlock(builder, context, options.cutoff, first, count, *row, block_stats[b]));
      if (!s.ok()) {
        std::lock_guard lock(error_mutex);
        if (error.ok()) error = std::move(s);
        cancelled = true;
      }
      const int64_t done = rows_done.fetch_add(count) + count;
      // Only thread 0 reports, so the callback never runs concurrently with itself.
      if (progress && ThreadIndex() == 0 && !progress("rows", done, n)) cancelled = true;
    }
  });
  if (!error.ok()) return error;
  if (cancelled) return absl::CancelledError("form-factor rows cancelled");
  RowBlockStats stats;
  for (const RowBlockStats& s : block_stats) stats.Merge(s);
  if (progress) progress("rows", n, n);
  return stats;
}

}  // namespace

absl::StatusOr<FormFactorResult> BuildFormFactors(const RowContext& context,
                                                  const FormFactorOptions& options,
                                                  const PhaseProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const uint32_t n = context.Unknowns();
  const uint32_t block_size = static_cast<uint32_t>(std::max(1, options.block_size));
  std::vector<RowBlock> blocks((n + block_size - 1) / block_size);
  const std::unique_ptr<RowBuilder> builder = MakeRowBuilder(context, options);
  absl::StatusOr<RowBlockStats> stats =
      BuildBlocks(*builder, context, options, progress, [&](uint32_t b, RowBlock block) {
        blocks[b] = std::move(block);
        return absl::OkStatus();
      });
  if (!stats.ok()) return stats.status();

  FormFactorResult result;
  result.matrix.cols = n;
  size_t nnz = 0;
  for (const RowBlock& block : blocks) nnz += block.col.size();
  result.matrix.Reserve(n, nnz);
  for (RowBlock& block : blocks) {
    result.matrix.Append(block);
    block = RowBlock{};
  }
  FinishRows(*builder, options.threads, result.matrix);
  result.stats = *stats;
  result.seconds = SecondsSince(start);
  return result;
}

void FinishRows(const RowBuilder& builder, int threads, CsrMatrix& rows) {
  if (const ReciprocalPairs* pairs = builder.Pairs()) pairs->Average(threads, rows);
}

absl::StatusOr<std::unique_ptr<RowStore>> FinishRows(const RowBuilder& builder, int threads,
                                                     std::unique_ptr<RowStore> rows,
                                                     const std::string& spill_directory) {
  const ReciprocalPairs* pairs = builder.Pairs();
  if (pairs == nullptr) return rows;
  const uint64_t budget = rows->budget() - std::min(rows->budget(), rows->MemoryBytes());
  auto averaged = std::make_unique<RowStore>(
      rows->cols(), budget, std::make_unique<FileBlockSpill>(spill_directory), rows->chunk_bytes());
  absl::StatusOr<SpilledAveraging> done =
      pairs->Average(threads, *rows, 2 * rows->chunk_bytes(), spill_directory, *averaged);
  if (!done.ok()) return done.status();
  return averaged;
}

absl::StatusOr<RowBuildSummary> BuildFormFactorsInto(const RowContext& context,
                                                     const FormFactorOptions& options,
                                                     std::unique_ptr<RowStore> store,
                                                     const std::string& spill_directory,
                                                     const PhaseProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  OrderedRowAppender appender(*store);
  const std::unique_ptr<RowBuilder> builder = MakeRowBuilder(context, options);
  absl::StatusOr<RowBlockStats> stats =
      BuildBlocks(*builder, context, options, progress,
                  [&](uint32_t b, RowBlock block) { return appender.Put(b, std::move(block)); });
  if (!stats.ok()) return stats.status();
  if (absl::Status s = appender.Finish(); !s.ok()) return s;
  absl::StatusOr<std::unique_ptr<RowStore>> rows =
      FinishRows(*builder, options.threads, std::move(store), spill_directory);
  if (!rows.ok()) return rows.status();
  return RowBuildSummary{*std::move(rows), *stats, SecondsSince(start)};
}

}  // namespace radflux
