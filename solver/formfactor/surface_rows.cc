#include "solver/formfactor/surface_rows.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>

#include "solver/core/parallel.h"
#include "solver/core/physical_memory.h"
#include "solver/core/seconds_since.h"
#include "solver/formfactor/blocker_bvh.h"
#include "solver/formfactor/shaft_cull.h"
#include "solver/formfactor/shaft_visibility.h"

namespace radflux {
namespace {

using Clock = std::chrono::steady_clock;

// F_ij with occlusion: the unoccluded factor, times the visible fraction when the pair's
// segments may meet a blocker. A pair taking one segment (far for its size) traces it at
// once: its walk through the hierarchy visits no more nodes than the shaft's would (the
// segment lies in the shaft) and an empty shaft leaves it unblocked, so F is the same. Other
// pairs are traced only when their shaft may hold a blocker. A segment tests the blocker that
// hid the previous one first (BlockerBvh::SegmentBlocked's `last`), kept across the pairs of
// a row: the next pair of a row is often a neighbour of the last behind the same building.
double PairFactor(const std::vector<SurfaceShape>& shapes, const BlockerBvh& blockers, uint32_t i,
                  uint32_t j, const PairIntegration& integration, uint32_t& last,
                  SurfaceRowsStats& stats) {
  const double f = UnoccludedViewFactor(shapes[i], shapes[j], integration, stats.pairs);
  if (f == 0 || !blockers.PairMayMeetBlockers(i, j)) return f;
  const auto blocked = [&](const Vec3& a, const Vec3& b) {
    return blockers.SegmentBlocked(a, b, i, j, last);
  };
  const uint64_t before = stats.segments;
  std::optional<double> seen =
      OneSegmentVisibleFraction(shapes[i], shapes[j], blocked, stats.segments);
  if (!seen) {
    if (!blockers.AnyInShaft(i, j)) return f;
    seen = VisibleFraction(shapes[i], shapes[j], blocked, stats.segments);
  }
  if (stats.segments > before) ++stats.traced_pairs;
  return f * *seen;
}

// Row i into `row` (size radiating): each factor times its target's opacity.
void BuildRow(const std::vector<SurfaceShape>& shapes, const BlockerBvh& blockers, uint32_t i,
              const PairIntegration& integration, std::span<double> row, SurfaceRowsStats& stats) {
  uint32_t last = BlockerBvh::kNoBlocker;
  for (uint32_t j = 0; j < row.size(); ++j) {
    row[j] = j == i
                 ? 0
                 : PairFactor(shapes, blockers, i, j, integration, last, stats) * shapes[j].opacity;
  }
}

// Row i of the upper triangle: A F for the pairs (i, j > i), each integrated over the one of
// the two with the smaller diameter (the far and middle rules measure distance in its size).
void BuildTriangleRow(const std::vector<SurfaceShape>& shapes, const BlockerBvh& blockers,
                      uint32_t i, const PairIntegration& integration, std::span<double> row,
                      SurfaceRowsStats& stats) {
  uint32_t last = BlockerBvh::kNoBlocker;
  for (uint32_t k = 0; k < row.size(); ++k) {
    const uint32_t j = i + 1 + k;
    const bool i_outer = shapes[i].diameter <= shapes[j].diameter;
    const uint32_t o = i_outer ? i : j, t = i_outer ? j : i;
    row[k] = shapes[o].area * PairFactor(shapes, blockers, o, t, integration, last, stats);
  }
}

size_t BlockRows(size_t radiating, const SurfaceRowsOptions& options) {
  const auto threads = static_cast<size_t>(ThreadCount(options.threads));
  size_t rows = 64 * threads;
  if (options.memory_limit > 0) {
    rows = std::min<size_t>(
        rows, options.memory_limit / (sizeof(double) * std::max<size_t>(radiating, 1)));
  }
  return std::max<size_t>(rows, 1);
}

void PrintProgress(const char* what, size_t done, size_t total, Clock::time_point start) {
  const double elapsed = SecondsSince(start);
  const double eta =
      done > 0 ? elapsed * static_cast<double>(total - done) / static_cast<double>(done) : 0;
  std::fprintf(stderr, "\rviewfactors: %s %zu/%zu (%.0f%%), %.0f s, ETA %.0f s   ", what, done,
               total, 100.0 * static_cast<double>(done) / static_cast<double>(total), elapsed, eta);
  if (done == total) std::fputc('\n', stderr);
}

size_t TriangleSize(size_t n) { return n * (n - 1) / 2; }

absl::Status StoppedError() { return absl::CancelledError("view-factor rows stopped"); }

// Offset of pair (i, j), i < j, in the packed upper triangle of an n x n matrix.
size_t TriangleIndex(size_t n, size_t i, size_t j) { return i * (2 * n - i - 1) / 2 + (j - i - 1); }

// The rows F_ij = min(1, A F_ij * opacity_j / A_i) of the packed triangle `af` of A F, to the
// sink in order, a block of kEmitBlockBytes at a time, filled in parallel in the order the
// triangle is stored: row i's part right of the diagonal is triangle row i, and its part left
// of it, for the block's rows side by side, runs along triangle row j (no column walks through
// a triangle larger than the caches).
constexpr size_t kEmitBlockBytes = size_t{8} << 20;
absl::Status EmitTriangleRows(const std::vector<SurfaceShape>& shapes, size_t n,
                              std::span<const double> af, int threads, const SurfaceRowSink& sink) {
  const size_t block = std::clamp<size_t>(kEmitBlockBytes / (sizeof(double) * n), 1, n);
  std::vector<double> rows(block * n);
  const auto factor = [&](size_t i, size_t j, double a) {
    return std::min(1.0, a * shapes[j].opacity / shapes[i].area);
  };
  for (size_t first = 0; first < n; first += block) {
    const size_t count = std::min(block, n - first);
    ParallelFor(static_cast<int64_t>(count), 1, threads, [&](int64_t b, int64_t e) {
      for (int64_t r = b; r < e; ++r) {  // the diagonal and right of it
        const size_t i = first + static_cast<size_t>(r);
        double* row = rows.data() + static_cast<size_t>(r) * n;
        row[i] = factor(i, i, 0);
        for (size_t j = i + 1; j < n; ++j) row[j] = factor(i, j, af[TriangleIndex(n, i, j)]);
      }
    });
    ParallelFor(static_cast<int64_t>(first + count), 64, threads, [&](int64_t b, int64_t e) {
      for (size_t j = static_cast<size_t>(b); j < static_cast<size_t>(e); ++j) {  // left of it
        for (size_t i = std::max(first, j + 1); i < first + count; ++i) {
          rows[(i - first) * n + j] = factor(i, j, af[TriangleIndex(n, j, i)]);
        }
      }
    });
    for (size_t r = 0; r < count; ++r) {
      if (absl::Status s = sink(std::span<const double>(rows.data() + r * n, n)); !s.ok()) return s;
    }
  }
  return absl::OkStatus();
}

// Every pair once (reciprocity: A_i F_ij = A_j F_ji), the triangle held whole, then the rows.
absl::Status BuildReciprocalRows(const std::vector<SurfaceShape>& shapes, size_t n,
                                 const BlockerBvh& blockers, const SurfaceRowsOptions& options,
                                 const SurfaceRowSink& sink, SurfaceRowsStats& stats) {
  const auto start = Clock::now();
  // Not zeroed: every entry is written below, and its pages are first touched there, by the
  // threads (no serial pass over a triangle of up to the memory budget).
  const std::unique_ptr<double[]> af(new double[TriangleSize(n)]);
  const size_t block = BlockRows(n, options);
  auto last_print = start;
  for (size_t first = 0; first < n; first += block) {
    const size_t count = std::min(block, n - first);
    std::vector<SurfaceRowsStats> per_thread(ThreadCount(options.threads));
    ParallelFor(static_cast<int64_t>(count), 1, options.threads, [&](int64_t b, int64_t e) {
      for (int64_t r = b; r < e; ++r) {
        const size_t i = first + r;
        if (i + 1 == n) continue;
        BuildTriangleRow(shapes, blockers, static_cast<uint32_t>(i), options.integration,
                         std::span<double>(af.get() + TriangleIndex(n, i, i + 1), n - i - 1),
                         per_thread[ThreadIndex()]);
      }
    });
    for (const SurfaceRowsStats& s : per_thread) stats.Merge(s);
    if (options.on_rows && !options.on_rows(first + count, n)) return StoppedError();
    const size_t done = TriangleSize(n) - TriangleSize(n - first - count);
    if (options.progress && (SecondsSince(last_print) > 1 || first + count == n)) {
      PrintProgress("pairs", done, TriangleSize(n), start);
      last_print = Clock::now();
    }
  }
  const std::span<const double> triangle(af.get(), TriangleSize(n));
  if (absl::Status s = EmitTriangleRows(shapes, n, triangle, options.threads, sink); !s.ok()) {
    return s;
  }
  stats.rows_seconds = SecondsSince(start);
  return absl::OkStatus();
}

}  // namespace

uint64_t SurfaceRowsBudget(uint64_t memory_limit) {
  if (memory_limit > 0) return memory_limit;
  const uint64_t physical = PhysicalMemoryBytes();
  return physical > 0
             ? static_cast<uint64_t>(kDefaultMemoryFraction * static_cast<double>(physical))
             : kFallbackBudget;
}

uint64_t TriangleBytes(size_t n) { return TriangleSize(n) * sizeof(double); }

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
  stats.budget = SurfaceRowsBudget(options.memory_limit);
  stats.triangle = TriangleBytes(radiating);
  stats.reciprocal = radiating > 1 && stats.triangle <= stats.budget;
  if (stats.reciprocal)
    return BuildReciprocalRows(shapes, radiating, blockers, options, sink, stats);
  start = Clock::now();
  const size_t block = BlockRows(radiating, options);
  std::vector<double> rows(block * radiating);
  auto last_print = start;
  for (size_t first = 0; first < radiating; first += block) {
    const size_t count = std::min(block, radiating - first);
    std::vector<SurfaceRowsStats> per_thread(ThreadCount(options.threads));
    ParallelFor(static_cast<int64_t>(count), 1, options.threads, [&](int64_t b, int64_t e) {
      for (int64_t r = b; r < e; ++r) {
        BuildRow(shapes, blockers, static_cast<uint32_t>(first + r), options.integration,
                 std::span<double>(rows.data() + r * radiating, radiating),
                 per_thread[ThreadIndex()]);
      }
    });
    for (const SurfaceRowsStats& s : per_thread) stats.Merge(s);
    if (options.on_rows && !options.on_rows(first + count, radiating)) return StoppedError();
    for (size_t r = 0; r < count; ++r) {
      absl::Status s = sink(std::span<const double>(rows.data() + r * radiating, radiating));
      if (!s.ok()) return s;
    }
    if (options.progress && (SecondsSince(last_print) > 1 || first + count == radiating)) {
      PrintProgress("rows", first + count, radiating, start);
      last_print = Clock::now();
    }
  }
  stats.rows_seconds = SecondsSince(start);
  return absl::OkStatus();
}

SurfaceRowPlan::SurfaceRowPlan(const std::vector<SurfaceShape>& shapes, size_t radiating,
                               const SurfaceRowsOptions& options, SurfaceRowsStats& stats)
    : shapes_(shapes), radiating_(radiating), options_(options) {
  const auto start = Clock::now();
  blockers_ = std::make_unique<BlockerBvh>(shapes, PotentialBlockers(shapes));
  stats.blockers = blockers_->size();
  stats.cull_seconds = SecondsSince(start);
  stats.budget = SurfaceRowsBudget(options.memory_limit);
  stats.triangle = TriangleBytes(radiating);
  stats.reciprocal = reciprocal_ = radiating > 1 && stats.triangle <= stats.budget;
}

SurfaceRowPlan::~SurfaceRowPlan() = default;

size_t SurfaceRowPlan::RowWidth(size_t i) const {
  return reciprocal_ ? radiating_ - i - 1 : radiating_;
}

size_t SurfaceRowPlan::BlockValues(size_t first, size_t count) const {
  if (!reciprocal_) return count * radiating_;
  return TriangleSize(radiating_ - first) - TriangleSize(radiating_ - first - count);
}

void SurfaceRowPlan::BuildBlock(size_t first, size_t count, std::span<double> values,
                                SurfaceRowsStats& stats) const {
  std::vector<SurfaceRowsStats> per_thread(ThreadCount(options_.threads));
  ParallelFor(static_cast<int64_t>(count), 1, options_.threads, [&](int64_t b, int64_t e) {
    for (int64_t r = b; r < e; ++r) {
      const size_t i = first + static_cast<size_t>(r);
      const std::span<double> row = values.subspan(BlockValues(first, i - first), RowWidth(i));
      if (reciprocal_) {
        BuildTriangleRow(shapes_, *blockers_, static_cast<uint32_t>(i), options_.integration, row,
                         per_thread[ThreadIndex()]);
      } else {
        BuildRow(shapes_, *blockers_, static_cast<uint32_t>(i), options_.integration, row,
                 per_thread[ThreadIndex()]);
      }
    }
  });
  for (const SurfaceRowsStats& s : per_thread) stats.Merge(s);
}

absl::Status SurfaceRowPlan::Emit(
    size_t block_rows,
    const std::function<absl::StatusOr<std::vector<double>>(size_t first)>& block,
    const SurfaceRowSink& sink) const {
  const size_t n = radiating_;
  std::vector<double> triangle;
  if (reciprocal_) triangle.reserve(TriangleSize(n));
  for (size_t first = 0; first < n; first += block_rows) {
    const size_t count = std::min(block_rows, n - first);
    absl::StatusOr<std::vector<double>> values = block(first);
    if (!values.ok()) return values.status();
    if (values->size() != BlockValues(first, count)) {
      return absl::InternalError("view-factor block of rows " + std::to_string(first) +
                                 " has the wrong number of values");
    }
    if (reciprocal_) {
      triangle.insert(triangle.end(), values->begin(), values->end());
      continue;
    }
    for (size_t r = 0; r < count; ++r) {
      if (absl::Status s = sink(std::span<const double>(values->data() + r * n, n)); !s.ok()) {
        return s;
      }
    }
  }
  if (!reciprocal_) return absl::OkStatus();
  return EmitTriangleRows(shapes_, n, triangle, options_.threads, sink);
}

}  // namespace radflux
