// Precision of the stored rows (issue 6): CsrMatrix keeps F_ij as float (accumulation and
// the solvers are double). On the hard cases, B from the float rows against B from the
// same rows in double, both by a dense double LU, isolates the storage rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "hard_cases.h"

namespace radflux {
namespace {

// Bound: rounding F_ij to float changes it by at most 2^-24 F_ij, so the gathered term
// rho_i sum_j F_ij B_j by at most rho 2^-24 s max(B) (s: largest row sum), and B by at most
// that amplified by ||(I - rho F)^-1||_inf <= 1 / (1 - rho s):
//   max |B_float - B_double| / max B <= rho s 2^-24 / (1 - rho s).
TEST(HardPrecision, FloatRowsChangeBWithinTheRoundingBound) {
  struct Case {
    const char* file;
    MeshOptions mesh;
    FormFactorMethod method;
  };
  const Case cases[] = {
      {"white_room_rho0999.obj", MeshOptions{120, 0}, FormFactorMethod::kAnalytic},
      {"white_room_rho099.obj", MeshOptions{120, 0}, FormFactorMethod::kMonteCarlo},
      {"wedge_10.obj", MeshOptions{0, 0.15}, FormFactorMethod::kAnalytic},
      {"slivers.obj", MeshOptions{}, FormFactorMethod::kAnalytic},
      {"tiny_emitter.obj", MeshOptions{0, 1.0 / 16}, FormFactorMethod::kAnalytic},
  };
  for (const Case& c : cases) {
    RowFixture fixture(LoadHardScene(c.file), c.mesh);
    const testing::DoubleRows rows = testing::BuildDoubleRows(fixture.context, HardOptions(c.method));
    const std::vector<double> bd = testing::DenseSolve(rows, fixture.attributes, false);
    const std::vector<double> bf = testing::DenseSolve(rows, fixture.attributes, true);
    double rho = 0, s = 0, b_max = 0, diff = 0, rel = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      double sum = 0;
      for (const auto& entry : rows[i]) sum += entry.second;
      s = std::max(s, sum);
      rho = std::max(rho, fixture.attributes.reflectance[i][0]);
      b_max = std::max(b_max, std::abs(bd[i]));
      diff = std::max(diff, std::abs(bf[i] - bd[i]));
      if (bd[i] != 0) rel = std::max(rel, std::abs(bf[i] / bd[i] - 1));
    }
    const double bound = rho * s * std::ldexp(1.0, -24) / (1 - rho * s);
    std::printf("precision %-24s %-12s n %4zu: max |B_f - B_d| / max B %.2e (bound %.2e), "
                "max relative %.2e\n",
                c.file, testing::Name(c.method).c_str(), rows.size(), diff / b_max, bound, rel);
    EXPECT_LE(diff / b_max, bound) << c.file;
  }
}

}  // namespace
}  // namespace radflux
