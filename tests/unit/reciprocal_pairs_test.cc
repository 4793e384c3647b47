// Reciprocity averaging of Monte Carlo rows (reciprocal_pairs.h): the averaged entries by the
// formula, row sums that stay their own rays' draw (a closed room's rows sum to 1), unbiased
// pairs. (The variance it removes is measured on the Cornell box, bench/RESULTS.md: between
// two plates a row's stratified rays already split it smoothly, and the averaging does not
// lower the per-patch variance there.)
#include "solver/formfactor/reciprocal_pairs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include "howell_closed_forms.h"
#include "solver/formfactor/row_rays.h"
#include "solver/sparse/file_block_spill.h"
#include "test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::RowFixture;
using testing::SceneFromObj;

CsrMatrix FromRows(const std::vector<std::vector<std::pair<uint32_t, float>>>& rows) {
  RowBlock block;
  for (const auto& row : rows) {
    for (const auto& [j, v] : row) block.Add(j, v);
    block.EndRow();
  }
  CsrMatrix m;
  m.cols = static_cast<uint32_t>(rows.size());
  m.Append(block);
  return m;
}

// Three cosine-ray rows (areas 1, 1, 2; rays 16, 16, 24 at k = 16, so 16, 16 and 12 rays per
// unit area) and an emitter (unknown 3), with hits h_01 = 4, h_02 = 6, h_10 = 2, h_12 = 8,
// h_20 = 3 (none on 1). Each pair's entry is (h_ij + h_ji) / (A_i (d_i + d_j)), the row's
// averaged entries scaled to the sum of its own: the emitter column and the row sums stay.
TEST(ReciprocalPairs, AveragesEachPairByRaysPerArea) {
  RowContext context;
  context.opaque_area = {1, 1, 2, 1};
  context.needs_row = {1, 1, 1, 1};
  context.mean_row_area = 4.0 / 3.0;  // RowRayCount(16, 1 or 2, 4/3) = 16 (the least) or 24
  ASSERT_EQ(RowRayCount(16, 1, context.mean_row_area, false), 16u);
  ASSERT_EQ(RowRayCount(16, 2, context.mean_row_area, false), 24u);
  CsrMatrix f = FromRows({{{1, 4 / 16.f}, {2, 6 / 16.f}, {3, 0.125f}},
                          {{0, 2 / 16.f}, {2, 8 / 16.f}},
                          {{0, 3 / 24.f}, {3, 0.25f}},
                          {{0, 0.5f}}});
  const std::vector<uint8_t> cosine = {1, 1, 1, 0};
  ReciprocalPairs(context, 16, cosine).Average(1, f);

  const double p01 = 6.0 / 32, p02 = 9.0 / 28;              // row 0: d 16+16, 16+12
  const double p10 = 6.0 / 32, p12 = 8.0 / 28;              // row 1
  const double p20 = 9.0 / (2 * 28), p21 = 8.0 / (2 * 28);  // row 2: A = 2
  const double s0 = (10.0 / 16) / (p01 + p02), s1 = (10.0 / 16) / (p10 + p12);
  const double s2 = (3.0 / 24) / (p20 + p21);
  EXPECT_NEAR(f.At(0, 1), p01 * s0, 1e-6);
  EXPECT_NEAR(f.At(0, 2), p02 * s0, 1e-6);
  EXPECT_FLOAT_EQ(f.At(0, 3), 0.125f);  // emitter column: as built
  EXPECT_NEAR(f.At(1, 0), p10 * s1, 1e-6);
  EXPECT_NEAR(f.At(1, 2), p12 * s1, 1e-6);
  EXPECT_NEAR(f.At(2, 0), p20 * s2, 1e-6);
  EXPECT_NEAR(f.At(2, 1), p21 * s2, 1e-6);  // a pair row 2's rays never met
  EXPECT_FLOAT_EQ(f.At(2, 3), 0.25f);
  EXPECT_FLOAT_EQ(f.At(3, 0), 0.5f);  // the emitter's row takes no part
  EXPECT_NEAR(f.RowSum(0), 10.0 / 16 + 0.125, 1e-6);
  EXPECT_NEAR(f.RowSum(1), 10.0 / 16, 1e-6);
  EXPECT_NEAR(f.RowSum(2), 3.0 / 24 + 0.25, 1e-6);
}

// Closed forms of reciprocity. Three plates of one area in a ring, each row's 16 rays
// meeting its neighbours 4 and 2 times the other way round (h_01 = 4, h_10 = 2, ...): every
// pair averages to 6 / 32, every row's averaged sum equals its own (scale 1), so the rows
// are exactly reciprocal, A_i F_ij = A_j F_ji, where the plain rows were off by 2x. Two
// plates alone: the one averaged entry of each row is scaled back to its own rays' sum, so
// the averaging leaves the pair as built (it only shares a row's sum out among its pairs).
TEST(ReciprocalPairs, SymmetricRingIsExactlyReciprocal) {
  RowContext context;
  context.opaque_area = {1, 1, 1};
  context.needs_row = {1, 1, 1};
  context.mean_row_area = 1;
  ASSERT_EQ(RowRayCount(16, 1, 1, false), 16u);
  CsrMatrix ring = FromRows({{{1, 4 / 16.f}, {2, 2 / 16.f}},
                             {{0, 2 / 16.f}, {2, 4 / 16.f}},
                             {{0, 4 / 16.f}, {1, 2 / 16.f}}});
  const std::vector<uint8_t> cosine = {1, 1, 1};
  ReciprocalPairs(context, 16, cosine).Average(1, ring);
  for (uint32_t i = 0; i < 3; ++i) {
    for (uint32_t j = 0; j < 3; ++j) {
      if (i == j) continue;
      EXPECT_EQ(ring.At(i, j), 6 / 32.f) << i << " " << j;
      EXPECT_EQ(ring.At(i, j), ring.At(j, i));
    }
  }

  context.opaque_area = {1, 1};
  context.needs_row = {1, 1};
  CsrMatrix pair = FromRows({{{1, 4 / 16.f}}, {{0, 2 / 16.f}}});
  ReciprocalPairs(context, 16, std::span<const uint8_t>(cosine).first(2)).Average(1, pair);
  EXPECT_EQ(pair.At(0, 1), 4 / 16.f);
  EXPECT_EQ(pair.At(1, 0), 2 / 16.f);
}

// The inward unit cube, 6 x 6 patches a face, no emitter: every cosine ray meets a face, so
// each row sums to 1, and still does after the averaging (a furnace's B stays exact); the
// averaged rows are nearly reciprocal (A_i F_ij = A_j F_ji up to the rows' scalings).
TEST(ReciprocalPairs, ClosedCubeRowsStillSumToOne) {
  RowFixture fixture(
      testing::InwardUnitCube({"white", "white", "white", "white", "white", "white"}),
      MeshOptions{216, 0});
  FormFactorOptions options;
  options.cutoff = 0;
  const CsrMatrix f = fixture.Rows(options);
  ASSERT_EQ(f.rows, 216u);
  double worst_sum = 0, worst_reciprocity = 0;
  for (uint32_t i = 0; i < f.rows; ++i) {
    worst_sum = std::max(worst_sum, std::abs(f.RowSum(i) - 1));
    for (uint32_t j : f.RowCols(i)) {
      const double a = fixture.mesh.patches[i].area * f.At(i, j);
      const double b = fixture.mesh.patches[j].area * f.At(j, i);
      worst_reciprocity = std::max(worst_reciprocity, std::abs(a - b) / std::max(a, b));
    }
  }
  std::printf("closed cube: worst |row sum - 1| %.2e, worst reciprocity %.3f\n", worst_sum,
              worst_reciprocity);
  EXPECT_LT(worst_sum, 1e-5);
  EXPECT_LT(worst_reciprocity, 0.5);  // scalings of about 1 +- 2 / sqrt(k) each; plain: 1
}

// The raw rows of the inward unit cube (6 x 6 patches a face), and a store of them that spills
// all but 8 KB in 4 KB chunks.
class StoredCube : public ::testing::Test {
 protected:
  StoredCube()
      : fixture_(testing::InwardUnitCube({"white", "white", "white", "white", "white", "white"}),
                 MeshOptions{216, 0}) {
    options_.reciprocal_pairs = false;
    raw_ = fixture_.Rows(options_);
  }
  std::unique_ptr<RowStore> Store() const {
    auto stored = std::make_unique<RowStore>(raw_.rows, 8 << 10,
                                             std::make_unique<FileBlockSpill>(""), 4 << 10);
    RowBlock block;
    for (uint32_t i = 0; i < raw_.rows; ++i) {
      for (size_t e = 0; e < raw_.RowCols(i).size(); ++e) {
        block.Add(raw_.RowCols(i)[e], raw_.RowValues(i)[e]);
      }
      block.EndRow();
    }
    EXPECT_TRUE(stored->Append(std::move(block)).ok());
    EXPECT_TRUE(stored->Finish().ok());
    EXPECT_GT(stored->SpilledBytes(), 0u);
    return stored;
  }
  std::vector<uint8_t> Cosine() const {
    std::vector<uint8_t> cosine(raw_.rows, 1);
    cosine[7] = 0;  // an unknown that takes no part
    return cosine;
  }

  RowFixture fixture_;
  FormFactorOptions options_;
  CsrMatrix raw_;
};

// Rows in a store that spills, averaged in ranges of one row, of 40 KB and all at once, are
// the rows averaged in memory, bit for bit.
TEST_F(StoredCube, StoredRowsInRangesAreTheRowsInMemory) {
  const ReciprocalPairs pairs(fixture_.context, options_.rays, Cosine());
  CsrMatrix memory = raw_;
  pairs.Average(1, memory);
  for (const uint64_t working_bytes : {uint64_t{1}, uint64_t{40} << 10, uint64_t{1} << 30}) {
    const std::unique_ptr<RowStore> stored = Store();
    RowStore averaged(raw_.rows, 0, std::make_unique<FileBlockSpill>(""), 4 << 10);
    const absl::StatusOr<SpilledAveraging> done =
        pairs.Average(2, *stored, working_bytes, "", averaged);
    ASSERT_TRUE(done.ok()) << done.status();
    EXPECT_EQ(done->ranges > 1, working_bytes < (uint64_t{1} << 30)) << working_bytes;
    ASSERT_EQ(averaged.rows(), raw_.rows);
    EXPECT_EQ(averaged.nnz(), memory.nnz());
    size_t mismatched_rows = 0;
    ASSERT_TRUE(averaged
                    .ForEach([&](const RowsView& rows) {
                      for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
                        const auto c = rows.RowCols(i), ec = memory.RowCols(i);
                        const auto v = rows.RowValues(i), ev = memory.RowValues(i);
                        mismatched_rows += !std::equal(c.begin(), c.end(), ec.begin(), ec.end()) ||
                                           !std::equal(v.begin(), v.end(), ev.begin(), ev.end());
                      }
                    })
                    .ok());
    EXPECT_EQ(mismatched_rows, 0u) << working_bytes;
  }
  uint32_t changed = 0;  // averaged indeed
  for (uint32_t i = 0; i < raw_.rows; ++i) {
    const auto v = memory.RowValues(i), rv = raw_.RowValues(i);
    changed += !std::equal(v.begin(), v.end(), rv.begin(), rv.end());
  }
  EXPECT_GT(changed, raw_.rows * 9 / 10);
}

// However many ranges (here one row each: 216), the averaging reads the store's spill three
// times and its back hits once: bytes read <= 3 x SpilledBytes() + 1.5 x Bytes() (reading the
// spill once per range, as it did, read it 216 + 1 times).
TEST_F(StoredCube, SpilledIoIsBoundedWhateverTheRanges) {
  const ReciprocalPairs pairs(fixture_.context, options_.rays, Cosine());
  const std::unique_ptr<RowStore> stored = Store();
  RowStore averaged(raw_.rows, 0, std::make_unique<FileBlockSpill>(""), 4 << 10);
  const absl::StatusOr<SpilledAveraging> done = pairs.Average(2, *stored, 1, "", averaged);
  ASSERT_TRUE(done.ok()) << done.status();
  EXPECT_EQ(done->ranges, 216);
  EXPECT_EQ(stored->read_stats().passes, 3);
  EXPECT_EQ(stored->read_stats().bytes, 3 * stored->SpilledBytes());
  EXPECT_EQ(done->bucket_bytes_read, done->bucket_bytes_written);
  EXPECT_GT(done->bucket_bytes_written, 0u);
  EXPECT_LE(done->bucket_bytes_written, stored->nnz() * 12);
  EXPECT_LE(stored->read_stats().bytes + done->bucket_bytes_read,
            3 * stored->SpilledBytes() + 3 * stored->Bytes() / 2);
}

// A bucket file that cannot be written fails the averaging plainly, naming where.
TEST_F(StoredCube, BucketFileErrorsFailTheAveraging) {
  const ReciprocalPairs pairs(fixture_.context, options_.rays, Cosine());
  const std::unique_ptr<RowStore> stored = Store();
  const std::string not_a_dir = ::testing::TempDir() + "/reciprocal_pairs_not_a_dir";
  std::ofstream(not_a_dir) << "x";
  RowStore averaged(raw_.rows, 0, std::make_unique<FileBlockSpill>(""), 4 << 10);
  const absl::StatusOr<SpilledAveraging> done = pairs.Average(1, *stored, 1, not_a_dir, averaged);
  ASSERT_FALSE(done.ok());
  EXPECT_EQ(done.status().code(), absl::StatusCode::kFailedPrecondition) << done.status();
  EXPECT_NE(done.status().message().find("cannot create a spill file in '" + not_a_dir + "'"),
            std::string::npos)
      << done.status();
  std::remove(not_a_dir.c_str());
}

// Two parallel unit squares 0.5 apart, 8 x 8 patches each: per patch of "a", the form factor
// to the half of "b" at x < 0, over 32 seeds, with and without the averaging. The area-weighted
// mean over "a" is half of Howell's closed form (symmetry) within 4 standard errors either
// way (unbiased); the per-patch variance over seeds is printed.
TEST(ReciprocalPairs, ParallelSquaresStayUnbiased) {
  const double d = 0.5;
  int next = 1;
  std::string obj =
      ObjQuad("a", "white", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += ObjQuad("b", "white", {{-.5, -.5, d}, {-.5, .5, d}, {.5, .5, d}, {.5, -.5, d}}, next);
  RowFixture fixture(SceneFromObj(obj), MeshOptions{128, 0});
  const double exact_half = testing::ParallelRectangles(1, 1, d) / 2;
  const int seeds = 32;
  std::vector<uint32_t> plate_a;
  std::vector<uint8_t> left_of_b(fixture.mesh.size(), 0);
  for (uint32_t p = 0; p < fixture.mesh.size(); ++p) {
    if (fixture.ObjectOf(p) == "a") plate_a.push_back(p);
    left_of_b[p] = fixture.ObjectOf(p) == "b" && fixture.mesh.patches[p].centroid.x < 0;
  }
  ASSERT_EQ(plate_a.size(), 64u);
  for (const bool averaged : {false, true}) {
    std::vector<double> sum(plate_a.size(), 0), sum2(plate_a.size(), 0);
    double total = 0, total2 = 0;
    for (int s = 1; s <= seeds; ++s) {
      FormFactorOptions options;
      options.cutoff = 0;
      options.seed = static_cast<uint64_t>(s);
      options.reciprocal_pairs = averaged;
      const CsrMatrix f = fixture.Rows(options);
      double q = 0, area = 0;
      for (size_t k = 0; k < plate_a.size(); ++k) {
        const uint32_t i = plate_a[k];
        double to_left = 0;
        const auto cols = f.RowCols(i);
        const auto vals = f.RowValues(i);
        for (size_t e = 0; e < cols.size(); ++e) to_left += left_of_b[cols[e]] ? vals[e] : 0;
        sum[k] += to_left;
        sum2[k] += to_left * to_left;
        q += fixture.mesh.patches[i].area * to_left;
        area += fixture.mesh.patches[i].area;
      }
      total += q / area;
      total2 += (q / area) * (q / area);
    }
    double variance = 0;
    for (size_t k = 0; k < plate_a.size(); ++k) {
      const double mean = sum[k] / seeds;
      variance += (sum2[k] / seeds - mean * mean) * seeds / (seeds - 1) / plate_a.size();
    }
    const double mean = total / seeds;
    const double error = std::sqrt(std::max(0.0, total2 / seeds - mean * mean) / (seeds - 1));
    std::printf("%s: F(a -> half of b) %.5f +- %.5f (exact %.5f), per-patch variance %.3e\n",
                averaged ? "averaged" : "plain   ", mean, error, exact_half, variance);
    EXPECT_NEAR(mean, exact_half, 4 * error + 1e-4) << averaged;
  }
}

}  // namespace
}  // namespace radflux
