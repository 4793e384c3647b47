// ReflectedIndirect: B less the emission and the light that came straight from an emission,
// against hand-worked rows, in memory and spilled.
#include "solver/solve/indirect_light.h"

#include <gtest/gtest.h>

#include "solver/pipeline.h"
#include "solver/sparse/row_store.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

// Unknown 0 a lamp (E = 1, rho = 0: no row); 1 and 2 reflect half (rho = 0.5) and see the
// lamp (F 0.3 and 0.1) and each other (F 0.2 and 0.4).
struct ThreePatches {
  CsrMatrix f;
  PatchAttributes p;
  ThreePatches() {
    f.rows = f.cols = 3;
    f.row_begin = {0, 0, 2, 4};
    f.col = {0, 2, 0, 1};
    f.value = {0.3f, 0.2f, 0.1f, 0.4f};
    p.area = {1, 1, 1};
    p.reflectance = {Rgb{0, 0, 0}, Rgb{0.5, 0.5, 0.5}, Rgb{0.5, 0.5, 0.5}};
    p.emission = {Rgb{1, 1, 1}, Rgb{0, 0, 0}, Rgb{0, 0, 0}};
  }
};

// I_1 = B_1 - rho F_10 E_0 = 0.4 - 0.15, I_2 = 0.3 - 0.05; the lamp, without a row, 0. A lamp
// that also reflects (B 1.1 against E 1) sends the extra 0.1 as indirect light: I is the same.
TEST(ReflectedIndirect, SubtractsTheLightStraightFromTheEmitters) {
  const ThreePatches s;
  const RadiositySystem system{&s.f, &s.p, nullptr};
  absl::StatusOr<std::vector<Rgb>> i =
      ReflectedIndirect(system, {Rgb{1, 1, 1}, Rgb{0.4, 0.4, 0.4}, Rgb{0.3, 0.3, 0.3}});
  ASSERT_TRUE(i.ok()) << i.status();
  EXPECT_DOUBLE_EQ((*i)[0][1], 0.0);
  EXPECT_NEAR((*i)[1][1], 0.25, 1e-7);
  EXPECT_NEAR((*i)[2][1], 0.25, 1e-7);
  i = ReflectedIndirect(system, {Rgb{1.1, 1.1, 1.1}, Rgb{0.4, 0.4, 0.4}, Rgb{0.3, 0.3, 0.3}});
  ASSERT_TRUE(i.ok());
  EXPECT_NEAR((*i)[1][0], 0.25, 1e-7);
  EXPECT_NEAR((*i)[2][2], 0.25, 1e-7);
}

// A B below what the lamp alone gives is clamped at 0, never negative light.
TEST(ReflectedIndirect, NeverNegative) {
  const ThreePatches s;
  const RadiositySystem system{&s.f, &s.p, nullptr};
  absl::StatusOr<std::vector<Rgb>> i =
      ReflectedIndirect(system, {Rgb{1, 1, 1}, Rgb{0.1, 0.1, 0.1}, Rgb{0.3, 0.3, 0.3}});
  ASSERT_TRUE(i.ok());
  EXPECT_EQ((*i)[1][0], 0.0);
}

// The same rows read from a RowStore give the same values; a B of the wrong size is refused.
TEST(ReflectedIndirect, ReadsStoredRowsAndRejectsBadSizes) {
  const ThreePatches s;
  RowStore store(3, 1 << 20, nullptr);
  RowBlock block;
  block.row_begin = s.f.row_begin;
  block.col = s.f.col;
  block.value = s.f.value;
  ASSERT_TRUE(store.Append(std::move(block)).ok());
  ASSERT_TRUE(store.Finish().ok());
  const RadiositySystem stored{nullptr, &s.p, &store};
  absl::StatusOr<std::vector<Rgb>> i =
      ReflectedIndirect(stored, {Rgb{1, 1, 1}, Rgb{0.4, 0.4, 0.4}, Rgb{0.3, 0.3, 0.3}});
  ASSERT_TRUE(i.ok()) << i.status();
  EXPECT_NEAR((*i)[2][0], 0.25, 1e-7);
  EXPECT_FALSE(ReflectedIndirect(stored, {Rgb{1, 1, 1}}).ok());
}

// A closed unit cube lit by its ceiling (rho 0.5 everywhere): RunJob's I per patch is, at
// convergence, rho times the irradiance from everything but emission, read off the very rows
// (sum over j of F_ij (B_j - E_j); the solve stops at 1e-9, the rows are floats: within 1e-5
// of B); and nothing when the caller says it draws no such picture.
TEST(ReflectedIndirect, RunJobFillsItPerPatchWhenAsked) {
  JobOptions options;
  options.mesh.target_patches = 150;
  options.solver.tolerance = 1e-9;
  const Scene scene =
      testing::InwardUnitCube({"white", "white", "white", "lamp", "white", "white"});
  absl::StatusOr<JobResult> result = RunJob(scene, options, {});
  ASSERT_TRUE(result.ok()) << result.status();
  const PatchAttributes& p = result->job->attributes;
  const std::vector<Rgb>& b = result->solve.radiosity;
  ASSERT_EQ(result->indirect.size(), result->job->mesh.size());
  for (uint32_t i = 0; i < p.size(); ++i) {
    double bounced_in = 0;
    const auto cols = result->form_factors.RowCols(i);
    const auto values = result->form_factors.RowValues(i);
    for (size_t k = 0; k < cols.size(); ++k) {
      bounced_in += values[k] * (b[cols[k]][0] - p.emission[cols[k]][0]);
    }
    EXPECT_NEAR(result->indirect[i][0], p.reflectance[i][0] * bounced_in, 1e-5 * b[i][0]) << i;
    EXPECT_LT(result->indirect[i][0], b[i][0] - p.emission[i][0] + 1e-12) << i;
  }
  options.find_indirect = false;
  result = RunJob(scene, options, {});
  ASSERT_TRUE(result.ok());
  EXPECT_TRUE(result->indirect.empty());
}

}  // namespace
}  // namespace radflux
