// Monte Carlo rows of a closed room sum to 1 in expectation, above 1 about half the time
// (light samples and cosine rays are independent estimates): the rows that are scaled back
// (RowContext::MaxRowSum) must be only those that would gain light, or B comes out biased
// low. Closed form: with rho uniform, sum_i A_i B_i = sum_i A_i E_i / (1 - rho).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "solver/pipeline.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

// A closed unit cube seen from inside, its ceiling the lamp (rho 0.5, Ke 1: E = pi), the
// rest white (rho 0.5).
Scene LitCube() {
  return testing::InwardUnitCube({"white", "white", "white", "white", "white", "lamp"});
}

// At k = 16 (noisy rows: the bias grows as the noise does), the mean over 8 seeds of
// sum A B is the closed form 2 pi within 0.5% and within 4 standard errors; scaling every
// row above 1 back to 1 made it 1.55% low (0.66% at the default k = 64).
TEST(ClosedRoomPower, SampledRowsKeepTheClosedFormTotalPower) {
  constexpr int kSeeds = 8;
  const double exact = std::numbers::pi / (1 - 0.5);
  std::vector<double> ratio;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    JobOptions options;
    options.mesh.target_patches = 400;
    options.form_factors.rays = 16;
    options.form_factors.seed = static_cast<uint64_t>(seed);
    options.solver.tolerance = 1e-8;
    absl::StatusOr<JobResult> result = RunJob(LitCube(), options);
    ASSERT_TRUE(result.ok()) << result.status();
    ASSERT_TRUE(result->solve.converged);
    const PreparedJob& job = *result->job;
    double power = 0;
    for (uint32_t p = 0; p < job.mesh.size(); ++p) {
      power += job.mesh.patches[p].area * result->solve.radiosity[p][0];
    }
    ratio.push_back(power / exact);
  }
  double mean = 0, mean2 = 0;
  for (double r : ratio) mean += r / kSeeds, mean2 += r * r / kSeeds;
  const double standard_error = std::sqrt((mean2 - mean * mean) / (kSeeds - 1));
  EXPECT_NEAR(mean, 1.0, 0.005);
  EXPECT_LT(std::abs(mean - 1), 4 * standard_error + 1e-4) << "standard error " << standard_error;
}

}  // namespace
}  // namespace radflux
