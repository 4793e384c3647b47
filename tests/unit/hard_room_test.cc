// Hard cases of issue 6 in closed and scaled rooms: the white furnace at rho -> 1, the
// cut-off's dropped energy in an enclosure, and unit (scale) invariance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "hard_cases.h"

namespace radflux {
namespace {

// Furnace: a closed room with rho and E = pi on every patch has B = pi / (1 - rho). Rows
// that sum to s_i in [1 - d, 1 + d] (d = worst row-sum error, here the analytic rows'
// ~1e-8 plus float storage) bound B between pi / (1 - rho (1 -+ d)), so the stated
// tolerance is rho d / (1 - rho - rho d) plus the solver's: residual 1e-10 times the
// condition 1 / (1 - rho). CG must converge; Jacobi's sweep count (~ln(tol) / ln(rho))
// is printed and must exceed CG's.
TEST(HardRoom, CgConvergesInWhiteRoomsWhereJacobiCrawls) {
  for (const auto& [file, rho] : {std::pair{"white_room_rho099.obj", 0.99},
                                  std::pair{"white_room_rho0999.obj", 0.999}}) {
    RowFixture fixture(LoadHardScene(file), MeshOptions{120, 0});
    const CsrMatrix f = fixture.Rows(HardOptions(FormFactorMethod::kAnalytic));
    ASSERT_TRUE(testing::AllFinite(f));
    const double d = testing::WorstRowSumError(f);
    const double exact = std::numbers::pi / (1 - rho);
    const double tolerance = rho * d / (1 - rho - rho * d) + 1e-10 / (1 - rho) + 1e-9;
    const double solver_tolerance = 1e-10;
    int iterations[2] = {0, 0};
    int k = 0;
    for (SolverMethod method : {SolverMethod::kConjugateGradient, SolverMethod::kJacobi}) {
      const SolveResult r = SolveOrDie(f, fixture.attributes, method, solver_tolerance, 200000);
      double worst = 0;
      for (const Rgb& b : r.radiosity) worst = std::max(worst, std::abs(b[0] / exact - 1));
      std::printf("white room rho %g, %zu patches, row-sum error %.2e: %-6s %6d iterations, "
                  "max |B/exact - 1| %.2e (bound %.2e)\n",
                  rho, fixture.mesh.size(), d, std::string(SolverName(method)).c_str(),
                  r.iterations, worst, tolerance);
      EXPECT_TRUE(r.converged) << SolverName(method) << " rho " << rho;
      EXPECT_LT(worst, tolerance) << SolverName(method) << " rho " << rho;
      iterations[k++] = r.iterations;
    }
    EXPECT_GT(iterations[1], 10 * iterations[0]) << "rho " << rho;
  }
}

// An enclosure whose rows sum to 1 before the cut-off: every row's lost energy
// 1 - sum_j F_ij equals what the cut-off dropped from it, which is at most (entries
// dropped) * cutoff <= n * cutoff; the reported max_row_dropped and dropped_sum agree
// with the rows (to the analytic rows' row-sum error plus float storage).
TEST(HardRoom, EnclosureDroppedEnergyWithinCutoffBound) {
  RowFixture fixture(LoadHardScene("white_room_rho099.obj"), MeshOptions{300, 0});
  const uint32_t n = static_cast<uint32_t>(fixture.mesh.size());
  // Every patch of the furnace glows and the cut-off never drops an emitter column (issue
  // 20); the analytic rows do not depend on the flags, so clear them to cut every entry.
  fixture.context.emitter.assign(n, 0);
  for (double cutoff : {1e-4, 1e-3}) {
    FormFactorOptions o = HardOptions(FormFactorMethod::kAnalytic);
    o.samples = 4;
    o.cutoff = cutoff;
    absl::StatusOr<FormFactorResult> rows = BuildFormFactors(fixture.context, o);
    ASSERT_TRUE(rows.ok()) << rows.status();
    double lost_sum = 0, worst_lost = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const double lost = 1 - rows->matrix.RowSum(i);
      lost_sum += lost;
      worst_lost = std::max(worst_lost, lost);
      const double bound = static_cast<double>(n - rows->matrix.RowCols(i).size()) * cutoff;
      EXPECT_LE(lost, bound + 1e-6) << "row " << i;
    }
    std::printf("enclosure n %u cutoff %g: dropped_sum %.4e (rows lose %.4e), max row %.4e "
                "(rows %.4e), bound n*cutoff %.2e\n",
                n, cutoff, rows->stats.dropped_sum, lost_sum, rows->stats.max_row_dropped,
                worst_lost, n * cutoff);
    EXPECT_GT(rows->stats.dropped_sum, 0);
    EXPECT_LE(rows->stats.max_row_dropped, n * cutoff);
    EXPECT_NEAR(rows->stats.dropped_sum, lost_sum, 1e-6 * n);
    EXPECT_NEAR(rows->stats.max_row_dropped, worst_lost, 1e-6);
  }
}

// Unit invariance: the same room in micrometres and in kilometres (coordinates 1e9 apart)
// has the same B per patch, W/m^2 not depending on the length unit: relative 1e-5. The
// floor patches under the block have no view at all (B = 0 up to CG round-off, ~1e-13 of
// max B), so B is compared relative to max(B_i, 1e-9 max B). monte_carlo and analytic give
// bit-identical rows at both scales (every offset and threshold is relative). hemicube does
// not reach 1e-5: its cell rays leave patch centroids of a regular mesh in grid-aligned
// directions and hit other faces' patches exactly on shared edges, where float rounding
// (different at the two scales) picks the neighbour or lets the ray through the seam (row
// sums differ by up to 7e-4); Embree's robust mode only halves it (measured 6e-4). Its
// stated bound is the achieved 2e-3; see bench/RESULTS.md "Hard cases".
TEST(HardScale, MicrometresAndKilometresGiveTheSameRadiosity) {
  RowFixture um(LoadHardScene("room_um.obj"), MeshOptions{160, 0});
  RowFixture km(LoadHardScene("room_km.obj"), MeshOptions{160, 0});
  ASSERT_EQ(um.mesh.size(), km.mesh.size());
  for (FormFactorMethod m : testing::kHardMethods) {
    FormFactorOptions o = HardOptions(m);
    o.samples = 4;
    o.rays = 256;
    o.hemicube_res = 32;
    const CsrMatrix fu = um.Rows(o), fk = km.Rows(o);
    const SolveResult bu = SolveOrDie(fu, um.attributes, SolverMethod::kConjugateGradient, 1e-12, 1000);
    const SolveResult bk = SolveOrDie(fk, km.attributes, SolverMethod::kConjugateGradient, 1e-12, 1000);
    double worst = 0, worst_f = 0, b_max = 0;
    for (const Rgb& b : bk.radiosity) b_max = std::max(b_max, b[0]);
    for (size_t i = 0; i < bu.radiosity.size(); ++i) {
      const double scale = std::max(std::abs(bk.radiosity[i][0]), 1e-9 * b_max);
      worst = std::max(worst, std::abs(bu.radiosity[i][0] - bk.radiosity[i][0]) / scale);
    }
    EXPECT_EQ(fu.nnz(), fk.nnz()) << Name(m);
    for (size_t e = 0; e < std::min(fu.nnz(), fk.nnz()); ++e) {
      worst_f = std::max(worst_f, std::abs(double(fu.value[e]) - double(fk.value[e])));
    }
    std::printf("scale um vs km %-12s: max |B_um/B_km - 1| %.2e, max |F_um - F_km| %.2e\n",
                Name(m).c_str(), worst, worst_f);
    EXPECT_LT(worst, m == FormFactorMethod::kHemicube ? 2e-3 : 1e-5) << Name(m);
  }
}

}  // namespace
}  // namespace radflux
