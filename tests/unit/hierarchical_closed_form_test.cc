// Hierarchical radiosity against closed forms: the gathered radiosity on a plate lit by an
// emitting plate is rho * E * F (Howell), within the tolerances the uniform analytic rows
// meet in formfactor_closed_form_test; and a closed furnace cube gives B = E / (1 - rho).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "hierarchical_test_scenes.h"
#include "howell_closed_forms.h"
#include "solver/hierarchical/hierarchical.h"

namespace radflux {
namespace {

using testing::GatheredFormFactor;
using testing::SolvedHierarchical;

TEST(HierarchicalClosedForm, ParallelSquaresWithinAnalyticTolerance) {
  for (double d : {0.5, 1.0, 2.0}) {
    const Scene scene = testing::EmittingParallelSquares(d);
    const double exact = testing::ParallelRectangles(1, 1, d);
    const HierarchicalResult r = SolvedHierarchical(scene, 1e-4, 16);
    const double f = GatheredFormFactor(scene, r);
    std::printf("parallel d=%g exact %.6f hierarchical %.6f (%zu leaves, %zu links)\n", d, exact, f,
                r.stats.leaves, r.stats.links);
    EXPECT_NEAR(f, exact, 0.002) << "d=" << d;  // the analytic builder's tolerance
    EXPECT_TRUE(r.solve.converged);
  }
}

TEST(HierarchicalClosedForm, PerpendicularPlatesWithinAnalyticTolerance) {
  const Scene scene = testing::EmittingPerpendicularPlates(1, 0.7, 1.3);
  const double exact = testing::PerpendicularRectangles(1, 0.7, 1.3);
  const HierarchicalResult r = SolvedHierarchical(scene, 1e-4, 16);
  const double f = GatheredFormFactor(scene, r);
  std::printf("perpendicular exact %.6f hierarchical %.6f (%zu leaves, %zu links)\n", exact, f,
              r.stats.leaves, r.stats.links);
  EXPECT_NEAR(f, exact, 0.004);
  EXPECT_GT(r.stats.leaves, 2u);  // the shared edge forces refinement
}

// Closed form: every face emits E = pi and reflects rho = 0.5 in a closed cube, so B = E /
// (1 - rho) = 2 pi everywhere. Looser than the uniform analytic rows (1e-6 there, whose rows
// average F over one point set and sum to 1): a leaf's links sit at several levels, each
// averaging F over its own element, so a leaf's sum is 1 only to the spread the refinement
// allows (link_epsilon 1e-3 with the spread oracle). Measured: RMS 1.7e-2, mean 4e-5.
TEST(HierarchicalClosedForm, FurnaceCubeWithinStatedTolerance) {
  const Scene scene = testing::FurnaceCube();
  const double exact = std::numbers::pi / (1 - 0.5);
  const HierarchicalResult r = SolvedHierarchical(scene, 1e-3, 16);
  const auto [rms, mean] = testing::LeafRelativeError(r, exact);
  std::printf("furnace: rms %.2e mean %.2e (%zu leaves, %zu links)\n", rms, mean, r.stats.leaves,
              r.stats.links);
  EXPECT_LT(rms, 0.025);
  EXPECT_LT(std::abs(mean), 0.003);
}

}  // namespace
}  // namespace radflux
