#include "solver/formfactor/surface_rows.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "solver/core/parallel.h"
#include "solver/formfactor/blocker_bvh.h"
#include "solver/formfactor/shaft_cull.h"
#include "solver/formfactor/shaft_visibility.h"

namespace radflux {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Row i into `row` (size radiating).
void BuildRow(const std::vector<SurfaceShape>& shapes, const BlockerBvh& blockers, uint32_t i,
              const PairIntegration& integration, std::span<double> row, SurfaceRowsStats& stats) {
  for (uint32_t j = 0; j < row.size(); ++j) {
    row[j] = j == i ? 0 : UnoccludedViewFactor(shapes[i], shapes[j], integration, stats.pairs);
    if (row[j] == 0 || !blockers.AnyInShaft(i, j)) continue;
    ++stats.traced_pairs;
    row[j] *= VisibleFraction(
        shapes[i], shapes[j],
        [&](const Vec3& a, const Vec3& b) { return blockers.SegmentBlocked(a, b, i, j); },
        stats.segments);
  }
}

size_t BlockRows(size_t radiating, const SurfaceRowsOptions& options) {
  const size_t threads = options.threads > 0 ? options.threads : DefaultThreadCount();
  size_t rows = 64 * threads;
  if (options.memory_limit > 0) {
    rows = std::min<size_t>(rows, options.memory_limit / (sizeof(double) * std::max<size_t>(radiating, 1)));
  }
  return std::max<size_t>(rows, 1);
}

void PrintProgress(size_t done, size_t total, Clock::time_point start) {
  const double elapsed = SecondsSince(start);
  const double eta = done > 0 ? elapsed * static_cast<double>(total - done) / static_cast<double>(done) : 0;
  std::fprintf(stderr, "\rviewfactors: rows %zu/%zu (%.0f%%), %.0f s, ETA %.0f s   ", done, total,
               100.0 * static_cast<double>(done) / static_cast<double>(total), elapsed, eta);
  if (done == total) std::fputc('\n', stderr);
}

}  // namespace

void SurfaceRowsStats::Merge(const SurfaceRowsStats& o) {
  pairs.Merge(o.pairs);
  traced_pairs += o.traced_pairs;
  segments += o.segments;
}

absl::Status BuildSurfaceRows(const std::vector<SurfaceShape>& shapes, size_t radiating,
                              const SurfaceRowsOptions& options, const SurfaceRowSink& sink,
                              SurfaceRowsStats& stats) {
  auto start = Clock::now();
  const BlockerBvh blockers(shapes, PotentialBlockers(shapes));
  stats.blockers = blockers.size();
  stats.cull_seconds = SecondsSince(start);
  start = Clock::now();
  const size_t block = BlockRows(radiating, options);
  std::vector<double> rows(block * radiating);
  auto last_print = start;
  for (size_t first = 0; first < radiating; first += block) {
    const size_t count = std::min(block, radiating - first);
    std::vector<SurfaceRowsStats> per_thread(DefaultThreadCount() + 1);
    ParallelFor(static_cast<int64_t>(count), 1, options.threads, [&](int64_t b, int64_t e) {
      for (int64_t r = b; r < e; ++r) {
        BuildRow(shapes, blockers, static_cast<uint32_t>(first + r), options.integration,
                 std::span<double>(rows.data() + r * radiating, radiating),
                 per_thread[ThreadIndex()]);
      }
    });
    for (const SurfaceRowsStats& s : per_thread) stats.Merge(s);
    for (size_t r = 0; r < count; ++r) {
      absl::Status s = sink(std::span<const double>(rows.data() + r * radiating, radiating));
      if (!s.ok()) return s;
    }
    if (options.progress && (SecondsSince(last_print) > 1 || first + count == radiating)) {
      PrintProgress(first + count, radiating, start);
      last_print = Clock::now();
    }
  }
  stats.rows_seconds = SecondsSince(start);
  return absl::OkStatus();
}

}  // namespace radflux
