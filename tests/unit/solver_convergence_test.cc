// Convergence of the iterative solvers against direct, and their rates.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "solver/solve/solver.h"
#include "tests/unit/solver_test_scenes.h"

namespace radflux {
namespace {

using testing::ClosedEqualArea;
using testing::ClosedUnequalArea;
using testing::kIterativeMethods;
using testing::Options;
using testing::TestSystem;

// Unequal areas, a different rho per band (one patch black in every band and rowless:
// an emitter that needs no row; a few black in band 1 only), two emitting bands.
TestSystem ColouredScene(uint32_t n, uint32_t seed) {
  TestSystem t = ClosedUnequalArea(n, 6, seed);
  for (uint32_t i = 0; i < n; ++i) {
    t.patches.reflectance[i] = {0.3 + 0.6 * ((i * 7) % 11) / 10.0, 0.8, 0.2};
    if (i % 9 == 4) t.patches.reflectance[i][1] = 0;
  }
  t.patches.reflectance[0] = Rgb{};
  t.patches.emission[0] = {10, 5, 0};
  t.patches.emission[n / 2] = {1, 2, 0};
  CsrMatrix f;  // drop row 0, as BuildFormFactors does for a patch with rho = 0
  f.cols = n;
  RowBlock block;
  for (uint32_t i = 0; i < n; ++i) {
    if (i != 0)
      for (size_t e = 0; e < t.f.RowCols(i).size(); ++e)
        block.Add(t.f.RowCols(i)[e], t.f.RowValues(i)[e]);
    block.EndRow();
  }
  f.Append(block);
  t.f = f;
  return t;
}

TEST(SolverConvergence, EveryIterativeSolverAgreesWithDirect) {
  const TestSystem t = ColouredScene(300, 3);
  const auto direct = Solve(t.View(), Options(SolverMethod::kDirect, 1e-12, 1));
  ASSERT_TRUE(direct.ok()) << direct.status();
  EXPECT_LT(direct->residual, 1e-13);
  EXPECT_EQ(direct->bands_solved, 2);
  for (SolverMethod method : kIterativeMethods) {
    const auto result = Solve(t.View(), Options(method, 1e-9, 100000));
    ASSERT_TRUE(result.ok()) << result.status();
    EXPECT_TRUE(result->converged) << SolverName(method);
    EXPECT_EQ(result->bands_solved, 2);
    // ||dB|| <= ||r|| / (1 - max rho) = 1e-8 here relative to ||E||; compare per patch.
    double worst = 0;
    for (size_t i = 0; i < t.patches.size(); ++i) {
      for (int band = 0; band < 2; ++band) {
        const double ref = direct->radiosity[i][band];
        worst = std::max(worst, std::abs(result->radiosity[i][band] - ref) / (ref + 1e-3));
      }
      EXPECT_EQ(result->radiosity[i][2], 0.0);  // band 2 emits nothing
    }
    EXPECT_LT(worst, 1e-6) << SolverName(method);
    EXPECT_LT(result->residual, 1e-7) << SolverName(method);
  }
}

TEST(SolverConvergence, CgNeedsAtMostATenthOfJacobiSweepsAtRho099) {
  TestSystem t = ClosedEqualArea(256, 0.99, 0);
  t.patches.emission[17] = {1, 1, 1};  // one emitter: not an eigenvector of F
  const auto jacobi = Solve(t.View(), Options(SolverMethod::kJacobi, 1e-6, 100000));
  const auto cg = Solve(t.View(), Options(SolverMethod::kConjugateGradient, 1e-6, 100000));
  ASSERT_TRUE(jacobi.ok() && cg.ok());
  EXPECT_TRUE(jacobi->converged);
  EXPECT_TRUE(cg->converged);
  EXPECT_LE(cg->residual, 1e-6);
  EXPECT_LE(10 * cg->iterations, jacobi->iterations)
      << "cg " << cg->iterations << " jacobi " << jacobi->iterations;
  RecordProperty("jacobi_sweeps", jacobi->iterations);
  RecordProperty("cg_iterations", cg->iterations);
  std::printf("rho=0.99 n=256 tol=1e-6: jacobi %d sweeps, cg %d iterations\n", jacobi->iterations,
              cg->iterations);
}

// Southwell stops on the same residual measure as every method (checked once per
// sweep-equivalent), while its unshot power only goes down.
TEST(SolverConvergence, SouthwellUnshotEnergyDecreasesMonotonically) {
  const TestSystem t = ColouredScene(400, 5);
  std::vector<double> unshot;
  const auto result = Solve(t.View(), Options(SolverMethod::kSouthwell, 1e-8, 100000),
                            [&](const SolveProgress& p) { unshot.push_back(p.unshot_fraction); });
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_TRUE(result->converged);
  ASSERT_EQ(unshot.size(), static_cast<size_t>(result->iterations));
  for (size_t k = 1; k < unshot.size(); ++k) ASSERT_LE(unshot[k], unshot[k - 1]) << k;
  EXPECT_EQ(result->unshot_fraction, unshot.back());
  EXPECT_LE(result->residual_history.back(), 1e-8);
  EXPECT_LE(result->residual, 1e-8);  // the final true residual of the original rows
}

TEST(SolverConvergence, JacobiResidualContractsByMaxRhoPerSweep) {
  TestSystem t = ClosedUnequalArea(200, 5, 11);
  double max_rho = 0;
  for (uint32_t i = 0; i < 200; ++i) {
    const double rho = 0.2 + 0.7 * ((i * 13) % 17) / 16.0;
    t.patches.reflectance[i] = {rho, rho, rho};
    max_rho = std::max(max_rho, rho);
  }
  t.patches.grey = true;
  t.patches.emission[3] = {4, 4, 4};
  const auto result = Solve(t.View(), Options(SolverMethod::kJacobi, 1e-12, 10000));
  ASSERT_TRUE(result.ok());
  // From B = 0 the measure is 1 for two sweeps (r = E against ||E||, then r = rho F E
  // against rho F E itself); from there the reflected part only grows, so the measure
  // contracts at least as fast as the residual.
  const auto& h = result->residual_history;
  ASSERT_GT(h.size(), 10u);
  for (size_t k = 2; k < h.size(); ++k)
    ASSERT_LE(h[k], max_rho * h[k - 1] * (1 + 1e-6) + 1e-15) << "sweep " << k;
}

TEST(SolverConvergence, WarmStartFromTheSolutionConvergesAtOnce) {
  const TestSystem t = ColouredScene(120, 9);
  const auto direct = Solve(t.View(), Options(SolverMethod::kDirect, 1e-12, 1));
  ASSERT_TRUE(direct.ok());
  for (SolverMethod method : kIterativeMethods) {
    SolverOptions o = Options(method, 1e-9, 1000);
    o.initial = &direct->radiosity;
    const auto result = Solve(t.View(), o);
    ASSERT_TRUE(result.ok());
    EXPECT_TRUE(result->converged) << SolverName(method);
    EXPECT_EQ(result->iterations, 1) << SolverName(method);
  }
}

TEST(SolverConvergence, CancellationStopsWithinOneSweep) {
  const TestSystem t = ColouredScene(300, 4);
  for (SolverMethod method : kIterativeMethods) {
    std::atomic<bool> cancel{false};
    SolverOptions o = Options(method, 0, 100000);
    o.cancel = &cancel;
    const auto result = Solve(t.View(), o, [&](const SolveProgress& p) {
      if (p.iteration == 3) cancel = true;
    });
    ASSERT_TRUE(result.ok()) << result.status();
    EXPECT_TRUE(result->cancelled) << SolverName(method);
    EXPECT_FALSE(result->converged);
    EXPECT_LE(result->iterations, 4) << SolverName(method);
    EXPECT_EQ(result->radiosity.size(), t.patches.size());
  }
}

TEST(SolverConvergence, BitIdenticalOnOneAndTwoThreads) {
  const TestSystem big = ColouredScene(10000, 8), small = ColouredScene(300, 8);
  for (SolverMethod method : testing::kAllMethods) {
    const TestSystem& t = method == SolverMethod::kDirect ? small : big;  // direct is O(n^3)
    const int sweeps = method == SolverMethod::kSouthwell ? 200 : 3000;   // batches are small
    const auto one = Solve(t.View(), Options(method, 1e-8, sweeps, 1));
    const auto two = Solve(t.View(), Options(method, 1e-8, sweeps, 2));
    ASSERT_TRUE(one.ok() && two.ok());
    EXPECT_EQ(one->iterations, two->iterations) << SolverName(method);
    EXPECT_EQ(one->residual_history, two->residual_history) << SolverName(method);
    EXPECT_TRUE(one->radiosity == two->radiosity) << SolverName(method);
  }
}

}  // namespace
}  // namespace radflux
