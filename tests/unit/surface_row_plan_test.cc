// SurfaceRowPlan: rows built a block at a time, in any order, then emitted, are the rows
// BuildSurfaceRows streams, bit for bit, whether each pair is integrated once (reciprocal)
// or rows one by one (a memory limit below the pair triangle): what lets the service
// checkpoint a view-factor job's blocks and resume it (issue 23).
#include <gtest/gtest.h>

#include <map>
#include <span>
#include <vector>

#include "solver/formfactor/surface_rows.h"
#include "surface_rows_collect.h"

namespace radflux {
namespace {

SurfaceShape Square(Vec3 origin, Vec3 u, Vec3 v) {
  return MakeSurfaceShape({origin, origin + u, origin + u + v, origin + v});
}

// The unit cube room, 2 x 2 squares per wall facing in, and a square floating inside it
// facing up (a blocker: some pairs are traced).
std::vector<SurfaceShape> RoomWithAFloatingSquare() {
  std::vector<SurfaceShape> shapes;
  const Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  struct Wall { Vec3 origin, u, v; };  // u x v points into the room
  for (const Wall& w : {Wall{{0, 0, 0}, x, y}, Wall{{0, 0, 1}, y, x}, Wall{{0, 0, 0}, z, x},
                        Wall{{0, 1, 0}, x, z}, Wall{{0, 0, 0}, y, z}, Wall{{1, 0, 0}, z, y}}) {
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        shapes.push_back(Square(w.origin + w.u * (a / 2.0) + w.v * (b / 2.0), w.u / 2, w.v / 2));
      }
    }
  }
  shapes.push_back(Square({0.3, 0.3, 0.5}, x * 0.4, y * 0.4));
  return shapes;
}

// The rows of `plan` from blocks of `block_rows` built last block first.
std::vector<std::vector<double>> PlanRows(const SurfaceRowPlan& plan, size_t block_rows,
                                          SurfaceRowsStats& stats) {
  const size_t n = plan.radiating();
  std::map<size_t, std::vector<double>> blocks;
  for (size_t first = (n - 1) / block_rows * block_rows;; first -= block_rows) {
    const size_t count = std::min(block_rows, n - first);
    std::vector<double>& values = blocks[first];
    values.resize(plan.BlockValues(first, count));
    plan.BuildBlock(first, count, values, stats);
    if (first == 0) break;
  }
  std::vector<std::vector<double>> rows;
  EXPECT_TRUE(plan.Emit(block_rows,
                        [&](size_t first) -> absl::StatusOr<std::vector<double>> {
                          return blocks.at(first);
                        },
                        [&](std::span<const double> row) {
                          rows.emplace_back(row.begin(), row.end());
                          return absl::OkStatus();
                        })
                  .ok());
  return rows;
}

void ExpectPlanRowsEqualStreamedRows(uint64_t memory_limit, bool reciprocal) {
  const std::vector<SurfaceShape> shapes = RoomWithAFloatingSquare();
  SurfaceRowsOptions options;
  options.memory_limit = memory_limit;
  SurfaceRowsStats streamed_stats, plan_stats;
  const std::vector<std::vector<double>> streamed =
      testing::CollectSurfaceRows(shapes, options, streamed_stats);
  const SurfaceRowPlan plan(shapes, shapes.size(), options, plan_stats);
  EXPECT_EQ(plan.reciprocal(), reciprocal);
  EXPECT_EQ(streamed_stats.reciprocal, reciprocal);
  EXPECT_GT(streamed_stats.traced_pairs, 0u) << "the floating square should block some pairs";
  for (size_t block_rows : {1, 5, 7, 25, 100}) {
    SurfaceRowsStats stats;
    const std::vector<std::vector<double>> rows = PlanRows(plan, block_rows, stats);
    ASSERT_EQ(rows.size(), streamed.size()) << block_rows;
    for (size_t i = 0; i < rows.size(); ++i) {
      ASSERT_EQ(rows[i], streamed[i]) << "row " << i << ", blocks of " << block_rows;
    }
    EXPECT_EQ(stats.segments, streamed_stats.segments) << "the same pairs traced";
  }
}

TEST(SurfaceRowPlan, ReciprocalBlocksGiveTheStreamedRowsBitForBit) {
  ExpectPlanRowsEqualStreamedRows(/*memory_limit=*/0, /*reciprocal=*/true);
}

TEST(SurfaceRowPlan, RowByRowBlocksGiveTheStreamedRowsBitForBit) {
  ExpectPlanRowsEqualStreamedRows(/*memory_limit=*/1, /*reciprocal=*/false);
}

}  // namespace
}  // namespace radflux
