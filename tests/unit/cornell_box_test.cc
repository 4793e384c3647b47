// The Cornell box end to end, in-process: the physics a person checks by eye, as numbers.
#include <gtest/gtest.h>

#include <map>

#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "solver/solve/energy_balance.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

class CornellBox : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    absl::StatusOr<Scene> scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
    ASSERT_TRUE(scene.ok());
    JobOptions options;
    options.mesh.target_patches = 1500;
    options.form_factors.rays = 256;
    options.solver.tolerance = 1e-6;
    absl::StatusOr<JobResult> result = RunJob(*std::move(scene), options);
    ASSERT_TRUE(result.ok()) << result.status();
    result_ = new JobResult(*std::move(result));
  }
  static void TearDownTestSuite() { delete result_; }

  // Area-weighted mean B of the patches of `object` (or group) satisfying `where`.
  template <typename Where>
  static Rgb MeanRadiosity(const std::string& group, Where where) {
    const PreparedJob& job = *result_->job;
    Rgb sum{};
    double area = 0;
    for (uint32_t p = 0; p < job.mesh.size(); ++p) {
      const Face& face = job.scene.faces[job.mesh.patches[p].face];
      if (job.scene.groups[face.group] != group || !where(job.mesh.patches[p])) continue;
      area += job.mesh.patches[p].area;
      for (int b = 0; b < kBands; ++b)
        sum[b] += job.mesh.patches[p].area * result_->solve.radiosity[p][b];
    }
    for (double& s : sum) s /= area;
    return sum;
  }
  static Rgb MeanRadiosity(const std::string& group) {
    return MeanRadiosity(group, [](const Patch&) { return true; });
  }

  static JobResult* result_;
};
JobResult* CornellBox::result_ = nullptr;

TEST_F(CornellBox, EnergyBalanceWithinHalfAPercent) {
  const EnergyBalance balance = ComputeEnergyBalance(
      RadiositySystem{&result_->form_factors, &result_->job->attributes}, result_->solve.radiosity);
  EXPECT_LT(balance.RelativeImbalance(), 0.005);
  for (int b = 0; b < kBands; ++b) EXPECT_GT(balance.escaped[b], 0);  // the front is open
}

TEST_F(CornellBox, RedWallTintsTheTallBlocksLeftSide) {
  // Sides of the tall block facing the red wall (+x) against those facing the green wall.
  const Rgb toward_red =
      MeanRadiosity("tall_block_sides", [](const Patch& p) { return p.normal.x > 0.5; });
  const Rgb toward_green =
      MeanRadiosity("tall_block_sides", [](const Patch& p) { return p.normal.x < -0.5; });
  const double red_ratio = toward_red[0] / toward_red[1];
  const double green_ratio = toward_green[0] / toward_green[1];
  std::printf("tall block: red/green toward red wall %.3f, toward green wall %.3f\n", red_ratio,
              green_ratio);
  EXPECT_GT(red_ratio, green_ratio * 1.2);
  // And the green wall's neighbour side is greener.
  EXPECT_GT(toward_green[1] / toward_green[0], toward_red[1] / toward_red[0]);
}

TEST_F(CornellBox, CeilingIsLitOnlyIndirectly) {
  // The ceiling faces down like the light: it gets no direct light, so it is darker than
  // the floor, yet not black (everything it gets was reflected first).
  const Rgb ceiling = MeanRadiosity("ceiling");
  const Rgb floor = MeanRadiosity("floor");
  for (int b = 0; b < kBands; ++b) {
    EXPECT_GT(ceiling[b], 0.05 * floor[b]);
    EXPECT_LT(ceiling[b], floor[b]);
  }
  // No row of a ceiling patch reaches the light.
  const PreparedJob& job = *result_->job;
  for (uint32_t p = 0; p < job.mesh.size(); ++p) {
    if (job.scene.groups[job.scene.faces[job.mesh.patches[p].face].group] != "ceiling") continue;
    for (uint32_t j : result_->form_factors.RowCols(p)) EXPECT_FALSE(job.rows.emitter[j]);
  }
}

TEST_F(CornellBox, SolverConvergedAndRowsAreSparse) {
  EXPECT_TRUE(result_->solve.converged);
  EXPECT_LE(result_->solve.residual, 1e-6);
  const size_t n = result_->job->mesh.size();
  EXPECT_LT(result_->form_factors.nnz(), n * n / 4);
}

}  // namespace
}  // namespace radflux
