// The job report of the refining solvers: hierarchical radiosity reports its elements and
// links (its memory against n) and says why it has no energy balance; adaptive meshing
// reports each pass; a plain job carries neither block.
#include <gtest/gtest.h>

#include "hierarchical_test_scenes.h"
#include "solver/pipeline.h"
#include "solver/report.h"

namespace radflux {
namespace {

JobResult RunOnSquares(const JobOptions& options) {
  absl::StatusOr<JobResult> result = RunJob(testing::EmittingParallelSquares(1.0), options);
  EXPECT_TRUE(result.ok()) << result.status();
  return *std::move(result);
}

TEST(JobReport, HierarchicalReportsItsLinksAndNoBalance) {
  JobOptions options;
  options.hierarchical.enabled = true;
  options.hierarchical.link_epsilon = 1e-4;
  options.hierarchical.min_area_fraction = 1e-3;
  JobResult result = RunOnSquares(options);
  ASSERT_TRUE(result.hierarchical.has_value());
  const HierarchicalStats& stats = *result.hierarchical;
  const nlohmann::json report = MakeJobReport(result, options, "squares");
  const nlohmann::json& h = report.at("hierarchical");
  EXPECT_GT(stats.links, 0u);
  EXPECT_EQ(h.at("links"), stats.links);
  EXPECT_EQ(h.at("leaves"), stats.leaves);
  EXPECT_EQ(h.at("link_bytes"), stats.link_bytes);
  EXPECT_EQ(h.at("patches"), result.job->mesh.size());
  EXPECT_DOUBLE_EQ(h.at("links_per_leaf").get<double>(),
                   static_cast<double>(stats.links) / stats.leaves);
  EXPECT_EQ(report.at("options").at("solver"), "hierarchical");
  EXPECT_EQ(report.at("options").at("min_element_area"), 1e-3);
  EXPECT_TRUE(report.at("energy_balance").contains("error"));
  EXPECT_FALSE(report.at("energy_balance").contains("ok"));
  EXPECT_FALSE(report.contains("adaptive"));
}

TEST(JobReport, AdaptiveReportsEveryPass) {
  JobOptions options;
  options.mesh.target_patches = 16;
  options.adaptive.passes = 2;
  options.adaptive.threshold = 0.05;
  JobResult result = RunOnSquares(options);
  const nlohmann::json report = MakeJobReport(result, options, "squares");
  const nlohmann::json& passes = report.at("adaptive");
  ASSERT_EQ(passes.size(), 3u);  // the first solve and two refinement passes
  for (size_t k = 0; k < passes.size(); ++k) {
    EXPECT_EQ(passes[k].at("patches"), result.adaptive_passes[k].patches);
    EXPECT_EQ(passes[k].at("split"), result.adaptive_passes[k].split);
    EXPECT_EQ(passes[k].at("rows_recomputed"), result.adaptive_passes[k].rows_recomputed);
  }
  EXPECT_GT(passes[2].at("patches").get<size_t>(), passes[0].at("patches").get<size_t>());
  EXPECT_EQ(report.at("options").at("adaptive_passes"), 2);
  EXPECT_TRUE(report.at("energy_balance").contains("ok"));
  EXPECT_FALSE(report.contains("hierarchical"));
}

TEST(JobReport, PlainJobHasNeitherBlock) {
  JobOptions options;
  options.mesh.target_patches = 16;
  JobResult result = RunOnSquares(options);
  const nlohmann::json report = MakeJobReport(result, options, "squares");
  EXPECT_FALSE(report.contains("hierarchical"));
  EXPECT_FALSE(report.contains("adaptive"));
  EXPECT_FALSE(report.at("options").contains("link_epsilon"));
  EXPECT_TRUE(report.at("energy_balance").contains("relative_imbalance"));
}

}  // namespace
}  // namespace radflux
