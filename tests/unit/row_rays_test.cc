// Rays per Monte Carlo row (solver/formfactor/row_rays.h): in proportion to the row's area,
// k on average, within [max(k / 4, min(k, kLeastRowRays)), 4 k].
#include "solver/formfactor/row_rays.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace radflux {
namespace {

TEST(RowRays, MeanAreaCountsOnlyTheRowsThatExist) {
  const std::vector<double> area = {1, 2, 3, 100};
  const std::vector<uint8_t> has_row = {1, 1, 1, 0};  // the last patch is black: no row
  EXPECT_DOUBLE_EQ(MeanRowArea(area, has_row), 2.0);
  EXPECT_DOUBLE_EQ(MeanRowArea(area, std::vector<uint8_t>(4, 0)), 0.0);
}

TEST(RowRays, InProportionToAreaWithinTheClamp) {
  EXPECT_EQ(RowRayCount(64, 1.0, 1.0, false), 64u);
  EXPECT_EQ(RowRayCount(64, 1.5, 1.0, false), 96u);
  EXPECT_EQ(RowRayCount(64, 0.5, 1.0, false), 32u);
  EXPECT_EQ(RowRayCount(64, 0.01, 1.0, false), 16u);    // k / 4
  EXPECT_EQ(RowRayCount(64, 100.0, 1.0, false), 256u);  // 4 k
  EXPECT_EQ(RowRayCount(256, 0.01, 1.0, false), 64u);   // k / 4 above kLeastRowRays
  // Below 64, k / 4 would leave a small row fewer than kLeastRowRays rays.
  EXPECT_EQ(RowRayCount(16, 0.01, 1.0, false), static_cast<uint32_t>(kLeastRowRays));
  EXPECT_EQ(RowRayCount(16, 2.0, 1.0, false), 32u);
  EXPECT_EQ(RowRayCount(8, 0.01, 1.0, false), 8u);  // never more than k at the low end
  EXPECT_EQ(RowRayCount(1, 0.01, 1.0, false), 1u);
  EXPECT_EQ(RowRayCount(64, 1.0, 0.0, false), 64u);  // no rows with area: k
}

// An emitter's row casts kEmitterRowRays k whatever its area: a lamp in its housing reflects
// light far brighter than the room's, and its share of the room's power follows.
TEST(RowRays, AnEmittersRowCastsItsFixedCount) {
  EXPECT_EQ(RowRayCount(64, 0.01, 1.0, true), static_cast<uint32_t>(kEmitterRowRays * 64));
  EXPECT_EQ(RowRayCount(64, 100.0, 1.0, true), static_cast<uint32_t>(kEmitterRowRays * 64));
  EXPECT_EQ(RowRayCount(16, 1.0, 0.0, true), static_cast<uint32_t>(kEmitterRowRays * 16));
  EXPECT_EQ(RowRayCount(0, 1.0, 1.0, true), 1u);
}

// F_ij towards a hidden unknown j is read from j's row where j has less area per ray than i:
// an emitter i casts its fixed count, so its own hits win where an area-sized row's would not.
TEST(RowRays, AHiddenColumnIsReadWhereItHasLessAreaPerRay) {
  // i: 0.1 of the mean area, 16 rays (0.00625 per ray) or 256 as an emitter (0.00039); j: 0.01,
  // 16 rays (0.000625 per ray).
  EXPECT_TRUE(ReadFromHiddenRow(64, 0.1, false, 0.01, 1.0));
  EXPECT_FALSE(ReadFromHiddenRow(64, 0.1, true, 0.01, 1.0));
  EXPECT_FALSE(ReadFromHiddenRow(64, 0.01, false, 0.1, 1.0));  // j has more area per ray
}

// A share that is not a finite number >= 0 (an infinite or NaN area) gets the budget, never
// an undefined conversion of NaN to an integer (0 rays: a row of nothing but its emitters).
TEST(RowRays, ANonFiniteShareGetsTheBudget) {
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(RowRayCount(64, nan, 1.0, false), 64u);
  EXPECT_EQ(RowRayCount(64, inf, 1.0, false), 64u);
  EXPECT_EQ(RowRayCount(64, 1.0, inf, false), 64u);
  EXPECT_EQ(RowRayCount(64, -1.0, 1.0, false), 64u);
  EXPECT_EQ(RowRayCount(0, 1.0, 1.0, false), 1u);  // a zero budget: one ray, not an inverted clamp
}

// Unclamped, the rays add up to k per row, and every unit of area gets the same rays.
TEST(RowRays, TheBudgetIsKPerRowAndFollowsArea) {
  const std::vector<double> area = {0.5, 0.75, 1.0, 1.25, 1.5};
  const std::vector<uint8_t> has_row(area.size(), 1);
  const double mean = MeanRowArea(area, has_row);
  uint32_t total = 0;
  for (double a : area) {
    const uint32_t k = RowRayCount(128, a, mean, false);
    total += k;
    EXPECT_NEAR(k / a, 128 / mean, 0.5 / a);  // rounding only
  }
  EXPECT_NEAR(total, 128.0 * area.size(), 2.5);
}

// A row's near-field factor follows its area share: all of it from the mean row's area on,
// ceil(factor * share) below, never under 1; a share RowAreaShare cannot tell is 1.
TEST(RowRays, NearFieldPointsFollowTheRowsArea) {
  EXPECT_EQ(RowNearFieldFactor(16, 1.0), 16);
  EXPECT_EQ(RowNearFieldFactor(16, 20.0), 16);  // a large wall's: never more than its factor
  EXPECT_EQ(RowNearFieldFactor(16, 0.3), 5);
  EXPECT_EQ(RowNearFieldFactor(16, 0.06), 1);  // a slot over a lamp
  EXPECT_EQ(RowNearFieldFactor(16, 0.0), 1);
  EXPECT_EQ(RowNearFieldFactor(1, 0.3), 1);
  EXPECT_DOUBLE_EQ(RowAreaShare(0.5, 2.0), 0.25);
  EXPECT_DOUBLE_EQ(RowAreaShare(0.5, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(RowAreaShare(std::nan(""), 1.0), 1.0);
  EXPECT_EQ(RowNearFieldFactor(16, RowAreaShare(1.0, std::numeric_limits<double>::infinity())), 16);
}

}  // namespace
}  // namespace radflux
