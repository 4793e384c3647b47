// Test helper: every row BuildSurfaceRows streams, kept in memory in row order.
#pragma once

#include <gtest/gtest.h>

#include <span>
#include <vector>

#include "solver/formfactor/surface_rows.h"

namespace radflux::testing {

// All rows between `shapes` (every shape radiates), one vector per row; the build must succeed.
inline std::vector<std::vector<double>> CollectSurfaceRows(const std::vector<SurfaceShape>& shapes,
                                                           const SurfaceRowsOptions& options,
                                                           SurfaceRowsStats& stats) {
  std::vector<std::vector<double>> f;
  EXPECT_TRUE(BuildSurfaceRows(shapes, shapes.size(), options,
                               [&](std::span<const double> row) {
                                 f.emplace_back(row.begin(), row.end());
                                 return absl::OkStatus();
                               },
                               stats)
                  .ok());
  EXPECT_EQ(f.size(), shapes.size());
  return f;
}

}  // namespace radflux::testing
