// View-factor outputs (solver/formfactor/view_factor_writer.h) read back: sparse lines plus
// the dropped column give every row's sum, SVF = max(0, 1 - sum), View3D's text layout; and
// the enclosure adjustment (enclosure_adjust.h) reaches closure and reciprocity; rows summing
// above 1 beyond their allowance are counted (`radflux viewfactors` exits 4 on them).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "solver/formfactor/enclosure_adjust.h"
#include "solver/formfactor/view_factor_job.h"
#include "solver/formfactor/view_factor_writer.h"

namespace radflux {
namespace {

const std::vector<std::vector<double>> kRows = {
    {0.0, 0.5, 0.004, 0.2},     // two entries kept, 0.004 dropped
    {0.3, 0.0, 0.001, 0.002},   // one kept
    {0.003, 0.002, 0.0, 0.001}, // none >= 0.01: its largest (0.003) is kept
    {0.0, 0.0, 0.0, 0.0},       // sees nothing: no line
};

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Write(ViewFactorFormat format, double min_vf, const std::string& svf = "") {
  // One file per test: ctest runs this file's tests at once, in processes of their own.
  const std::string path = testing::TempDir() + "/vf_out_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                           ".txt";
  const ViewFactorOutput output{format, path, min_vf, svf};
  const ViewFactorSurfaces surfaces{
      {"a", "b,c", "d", "e"}, {1, 2, 0.5, 4}, {0.9, 0.999, 1, 0.5}, false, false};
  absl::StatusOr<std::unique_ptr<ViewFactorWriter>> writer =
      ViewFactorWriter::Open(output, surfaces);
  EXPECT_TRUE(writer.ok()) << writer.status();
  for (const auto& row : kRows) EXPECT_TRUE((*writer)->WriteRow(row).ok());
  EXPECT_TRUE((*writer)->Close().ok());
  return ReadAll(path);
}

TEST(ViewFactorOutput, SparseLinesPlusDroppedColumnGiveEveryRowSum) {
  std::istringstream lines(Write(ViewFactorFormat::kSparse, 0.01));
  std::map<int, double> sum, dropped;
  std::map<int, int> count;
  int i, j, previous = 0;
  double f, d;
  while (lines >> i >> j >> f >> d) {
    EXPECT_GE(i, previous);  // rows ascending
    previous = i;
    sum[i] += f;
    dropped[i] = d;
    ++count[i];
  }
  EXPECT_EQ(count, (std::map<int, int>{{1, 2}, {2, 1}, {3, 1}}));
  for (int row = 1; row <= 3; ++row) {
    double full = 0;
    for (double v : kRows[row - 1]) full += v;
    EXPECT_NEAR(sum[row] + dropped[row], full, 1e-9) << row;
  }
  EXPECT_NEAR(dropped[3], 0.003, 1e-12);  // 0.002 + 0.001; the largest, 0.003, is kept
}

TEST(ViewFactorOutput, SkyViewFactorIsOneMinusRowSum) {
  const std::string svf = testing::TempDir() + "/svf.txt";
  Write(ViewFactorFormat::kCsv, 0, svf);
  std::istringstream lines(ReadAll(svf));
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header, "# sky view factors");
  for (const auto& row : kRows) {
    double value, sum = 0;
    for (double v : row) sum += v;
    ASSERT_TRUE(lines >> value);
    EXPECT_NEAR(value, 1 - sum, 1e-6);
  }
  double extra;
  EXPECT_FALSE(lines >> extra);
}

TEST(ViewFactorOutput, View3dTextLayout) {
  std::istringstream lines(Write(ViewFactorFormat::kView3d, 0));
  std::string header, areas, row, emit;
  std::getline(lines, header);
  EXPECT_EQ(header, "radflux 3.2 0 0 0 4           ");  // 30 characters, as View3D pads
  std::getline(lines, areas);
  EXPECT_EQ(areas, "1 2 0.5 4");
  std::getline(lines, row);
  EXPECT_EQ(row, "0.000000 0.500000 0.004000 0.200000");
  for (int k = 0; k < 3; ++k) std::getline(lines, row);
  EXPECT_EQ(row, "0.000000 0.000000 0.000000 0.000000");
  std::getline(lines, emit);
  EXPECT_EQ(emit, "0.900 0.999 1.000 0.500");
  EXPECT_FALSE(std::getline(lines, row));
}

// View3D's rows are printf's "%.6f", character for character, for values of every size a
// view factor takes, values next to a rounding tie (x.xxxxxx5 and its neighbours), and values
// outside [0, 1000) (the writer's fast path hands those to to_chars).
TEST(ViewFactorOutput, View3dRowsArePrintfsFixedSixDecimals) {
  std::vector<double> row;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0, 1), exponent(-12, 0);
  for (int k = 0; k < 20000; ++k) row.push_back(k % 2 ? unit(rng) : std::pow(10, exponent(rng)));
  for (int k = 0; k < 2000; ++k) {
    const double tie = (std::floor(unit(rng) * 1e6) + 0.5) / 1e6;
    for (double v : {tie, std::nextafter(tie, 0.0), std::nextafter(tie, 1.0)}) row.push_back(v);
  }
  for (double v : {0.0, -0.0, 1.0, 0.9999995, 5e-7, 4.9999999999e-7, 999.9999996, 1000.0, 1e9,
                   -0.25}) {
    row.push_back(v);
  }
  const size_t n = static_cast<size_t>(std::ceil(std::sqrt(static_cast<double>(row.size()))));
  while (row.size() < n * n) row.push_back(unit(rng));  // n rows of n values
  const std::string path = testing::TempDir() + "/vf_fixed6.txt";
  const ViewFactorSurfaces surfaces{std::vector<std::string>(n, "s"), std::vector<double>(n, 1),
                                    std::vector<double>(n, 1), false, false};
  absl::StatusOr<std::unique_ptr<ViewFactorWriter>> writer =
      ViewFactorWriter::Open({ViewFactorFormat::kView3d, path, 0, ""}, surfaces);
  ASSERT_TRUE(writer.ok()) << writer.status();
  for (size_t r = 0; r < n; ++r) {
    ASSERT_TRUE((*writer)->WriteRow(std::span<const double>(row).subspan(r * n, n)).ok());
  }
  ASSERT_TRUE((*writer)->Close().ok());
  std::istringstream lines(ReadAll(path));
  std::string line, field;
  for (int k = 0; k < 2; ++k) std::getline(lines, line);  // header, areas
  for (size_t r = 0; r < n; ++r) {
    ASSERT_TRUE(std::getline(lines, line));
    std::istringstream fields(line);
    for (size_t c = 0; c < n; ++c) {
      const double v = row[r * n + c];
      ASSERT_TRUE(fields >> field);
      char expected[64];
      std::snprintf(expected, sizeof(expected), "%.6f", v);
      ASSERT_EQ(field, expected) << std::hexfloat << v;
    }
    EXPECT_FALSE(fields >> field);
  }
}

TEST(ViewFactorOutput, CsvIsDenseAndNamed) {
  std::istringstream lines(Write(ViewFactorFormat::kCsv, 0));
  std::string header, first;
  std::getline(lines, header);
  EXPECT_EQ(header, "from,a,\"b,c\",d,e");
  std::getline(lines, first);
  EXPECT_EQ(first, "a,0,0.5,0.004,0.2");
}

TEST(ViewFactorOutput, UnwritableFileIsNamed) {
  absl::StatusOr<std::unique_ptr<ViewFactorWriter>> writer = ViewFactorWriter::Open(
      {ViewFactorFormat::kCsv, "/nonexistent-dir/x.csv", 0, ""}, {{"a"}, {1}, {1}, false, false});
  ASSERT_FALSE(writer.ok());
  EXPECT_NE(writer.status().message().find("/nonexistent-dir/x.csv"), std::string::npos);
}

// The unit cube's six faces: F to the opposite face 0.19982 (Howell C-11, a = b = c = 1),
// to each adjacent face (1 - 0.19982) / 4. Perturbed by a few percent, then adjusted.
TEST(RowSumCheck, CountsRowsAboveOnePlusAllowanceAndKeepsTheWorst) {
  RowSumCheck check;
  check.allowance = 0.01;
  const std::vector<std::vector<double>> rows = {
      {0.5, 0.5}, {0.5, 0.509}, {0.6, 0.5}, {0.2, 0.3}, {0.7, 0.32}};
  for (size_t i = 0; i < rows.size(); ++i) check.Add(i, rows[i]);
  EXPECT_EQ(check.rows_over, 2u);  // 1.1 and 1.02; 1.009 is within the allowance
  EXPECT_EQ(check.worst_row, 2u);
  EXPECT_DOUBLE_EQ(check.worst_sum, 1.1);
}

TEST(EnclosureAdjust, ReachesClosureAndReciprocityAndStaysNearTheTruth) {
  const double opposite = 0.1998243, adjacent = (1 - opposite) / 4;
  std::vector<std::vector<double>> f(6, std::vector<double>(6));
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      if (i == j) continue;
      const double exact = (i / 2 == j / 2) ? opposite : adjacent;  // faces 2k, 2k+1 opposite
      f[i][j] = exact * (1 + 0.03 * std::sin(7.0 * i + 3.0 * j));
    }
  }
  const std::vector<double> area(6, 1.0);
  EnclosureAdjustment a = AdjustEnclosure(f, area);
  EXPECT_GT(a.before.max_closure, 1e-3);
  EXPECT_GT(a.before.max_reciprocity, 1e-3);
  EXPECT_TRUE(a.converged);
  EXPECT_LT(a.after.max_closure, 1e-7);
  EXPECT_LT(a.after.max_reciprocity, 1e-12);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(f[i][i], 0);
    for (int j = 0; j < 6; ++j) {
      if (i != j) {
        EXPECT_NEAR(f[i][j], (i / 2 == j / 2) ? opposite : adjacent, 0.01);
      }
    }
  }
}

}  // namespace
}  // namespace radflux
