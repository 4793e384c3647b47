// Solver API: names, input checks, bands, known patches, snapshots, reciprocity report.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/solve/solver.h"
#include "tests/unit/solver_test_scenes.h"

namespace radflux {
namespace {

using testing::ClosedEqualArea;
using testing::kAllMethods;
using testing::Options;
using testing::TestSystem;

TEST(SolverApi, NamesRoundTrip) {
  for (SolverMethod method : kAllMethods) EXPECT_EQ(ParseSolver(SolverName(method)), method);
  EXPECT_EQ(SolverName(SolverMethod::kConjugateGradient), "cg");
  EXPECT_EQ(ParseSolver("gauss_seidel"), SolverMethod::kGaussSeidel);
  EXPECT_FALSE(ParseSolver("sor").has_value());
}

TEST(SolverApi, RejectsBadInputWithStatus) {
  TestSystem t = ClosedEqualArea(32, 0.5, 1);
  EXPECT_EQ(Solve({nullptr, &t.patches}, {}).status().code(), absl::StatusCode::kInvalidArgument);
  std::vector<Rgb> wrong_size(5);
  SolverOptions o;
  o.initial = &wrong_size;
  EXPECT_EQ(Solve(t.View(), o).status().code(), absl::StatusCode::kInvalidArgument);
  t.patches.reflectance[3][1] = 1.5;
  EXPECT_EQ(Solve(t.View(), {}).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(SolverApi, DirectRefusesLargeSystems) {
  const TestSystem t = ClosedEqualArea(kMaxDirectPatches + 1, 0.5, 1);
  const auto result = Solve(t.View(), Options(SolverMethod::kDirect, 1e-9, 1));
  EXPECT_EQ(result.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(result.status().message().find("4000"), std::string_view::npos);
}

TEST(SolverApi, ZeroReflectancePatchesKeepTheirEmission) {
  TestSystem t = ClosedEqualArea(64, 0.7, 1);
  for (uint32_t i = 0; i < 64; i += 5) t.patches.reflectance[i] = Rgb{};
  t.patches.emission[5] = {3, 3, 3};
  for (SolverMethod method : kAllMethods) {
    const auto result = Solve(t.View(), Options(method, 1e-10, 100000));
    ASSERT_TRUE(result.ok()) << result.status();
    for (uint32_t i = 0; i < 64; i += 5)
      EXPECT_NEAR(result->radiosity[i][0], t.patches.emission[i][0], 1e-12) << SolverName(method);
    EXPECT_GT(result->radiosity[1][0], 1.0) << SolverName(method);
  }
}

TEST(SolverApi, GreySceneSolvesOneBandAndDarkBandsNone) {
  TestSystem t = ClosedEqualArea(64, 0.6, 1);
  for (SolverMethod method : kAllMethods) {
    const auto result = Solve(t.View(), Options(method, 1e-9, 100000));
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->bands_solved, 1) << SolverName(method);
    for (const Rgb& b : result->radiosity) EXPECT_TRUE(IsGrey(b));
  }
  t.patches.grey = false;
  for (auto& e : t.patches.emission) e[2] = 0;
  t.patches.reflectance[0][1] = 0.3;
  const auto result = Solve(t.View(), Options(SolverMethod::kConjugateGradient, 1e-9, 1000));
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->bands_solved, 2);
  for (const Rgb& b : result->radiosity) EXPECT_EQ(b[2], 0.0);
  for (auto& e : t.patches.emission) e = Rgb{};
  const auto dark = Solve(t.View(), Options(SolverMethod::kJacobi, 1e-9, 1000));
  ASSERT_TRUE(dark.ok());
  EXPECT_EQ(dark->bands_solved, 0);
  EXPECT_EQ(dark->iterations, 0);
  EXPECT_TRUE(dark->converged);
}

TEST(SolverApi, SnapshotsOnlyEveryNIterationsWithAllBands) {
  TestSystem t = ClosedEqualArea(64, 0.9, 0);
  t.patches.emission[7] = {1, 1, 1};
  for (SolverMethod method : {SolverMethod::kJacobi, SolverMethod::kSouthwell,
                              SolverMethod::kConjugateGradient, SolverMethod::kGaussSeidel}) {
    SolverOptions o = Options(method, 0, 12);
    o.snapshot_every = 4;
    std::vector<int> with_snapshot;
    int calls = 0;
    const auto result = Solve(t.View(), o, [&](const SolveProgress& p) {
      ++calls;
      EXPECT_EQ(p.iteration, calls);
      if (p.snapshot == nullptr) return;
      with_snapshot.push_back(p.iteration);
      EXPECT_EQ(p.snapshot->size(), 64u);
      EXPECT_GT((*p.snapshot)[7][2], 0.0);  // band 2 filled from the grey lane
    });
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(calls, 12) << SolverName(method);
    EXPECT_EQ(with_snapshot, (std::vector<int>{4, 8, 12})) << SolverName(method);
  }
}

TEST(SolverApi, SouthwellSnapshotIncludesAmbientTerm) {
  const TestSystem t = ClosedEqualArea(64, 0.9, 1);
  SolverOptions o = Options(SolverMethod::kSouthwell, 0, 1);
  o.snapshot_every = 1;
  double snapshot_sum = 0;
  const auto result = Solve(t.View(), o, [&](const SolveProgress& p) {
    for (const Rgb& b : *p.snapshot) snapshot_sum += b[0];
  });
  ASSERT_TRUE(result.ok());
  double b_sum = 0;
  for (const Rgb& b : result->radiosity) b_sum += b[0];
  // Uniform furnace: B + ambient is exact after any number of shots (sum = 64 E / (1 - rho)).
  EXPECT_NEAR(snapshot_sum, 64 * 1 / (1 - 0.9), 1e-9);
  EXPECT_LT(b_sum, snapshot_sum - 1);
}

TEST(SolverApi, CgReportsReciprocityAndStillSolvesTheGivenRows) {
  TestSystem t = ClosedEqualArea(64, 0.8, 1);
  std::vector<std::map<uint32_t, double>> rows(64);
  for (uint32_t i = 0; i < 64; ++i)
    for (size_t e = 0; e < t.f.RowCols(i).size(); ++e)
      rows[i][t.f.RowCols(i)[e]] = t.f.RowValues(i)[e];
  const uint32_t j = rows[0].begin()->first, k = std::next(rows[1].begin())->first;
  rows[0][j] = 0.125 * 1.1;  // A_0 F_0j is 10% above A_j F_j0: error 0.1 / 1.1
  rows[k].erase(1);          // F_1k stored, F_k1 not: one one-sided pair
  t.f = testing::FromRows(rows);
  const auto cg = Solve(t.View(), Options(SolverMethod::kConjugateGradient, 1e-11, 1000));
  const auto direct = Solve(t.View(), Options(SolverMethod::kDirect, 1e-11, 1));
  ASSERT_TRUE(cg.ok() && direct.ok());
  EXPECT_NEAR(cg->reciprocity_error, 0.1 / 1.1, 1e-6);
  EXPECT_EQ(cg->one_sided_pairs, 1);
  EXPECT_TRUE(cg->converged);
  for (size_t i = 0; i < 64; ++i)
    EXPECT_NEAR(cg->radiosity[i][0], direct->radiosity[i][0], 1e-8 * direct->radiosity[i][0]);
}

TEST(SolverApi, RelativeResidualOfTheExactFurnaceIsZero) {
  const TestSystem t = ClosedEqualArea(64, 0.5, 1);
  const std::vector<Rgb> exact(64, Rgb{2, 2, 2});
  EXPECT_NEAR(RelativeResidual(t.View(), exact), 0, 1e-15);
  const std::vector<Rgb> zero(64, Rgb{});
  EXPECT_NEAR(RelativeResidual(t.View(), zero), 1, 1e-15);
}

}  // namespace
}  // namespace radflux
