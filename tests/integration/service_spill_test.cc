// radfluxd with a per-job memory limit (--max-memory) too small for a job's rows: the job
// runs with its rows spilled to its directory of the job store and streamed back during the
// solve, and computes exactly what the in-memory gauss_seidel solve computes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"
#include "wire/proto_convert.h"

namespace radflux {
namespace {

using testing::ExpectBitIdentical;
using testing::InProcess;
using testing::kMtl;
using testing::kObj;
using testing::SmallOptions;

class ServiceSpillTest : public testing::ServiceFixture {};

// EstimateJobBytes of the Cornell box with `proto`, its rows in memory (row_budget 0) or
// spilled beyond `row_budget` bytes.
uint64_t Estimate(const v1::SolveOptions& proto, uint64_t row_budget) {
  absl::StatusOr<JobOptions> options = FromProto(proto);
  absl::StatusOr<Scene> scene = LoadObjText(kObj, kMtl, "cornell_box.obj");
  EXPECT_TRUE(options.ok() && scene.ok());
  options->spill.memory_limit = row_budget;
  return EstimateJobBytes(*scene, *options);
}

// A --max-memory that leaves the job 64 KiB of rows in memory: far below the rows of
// about 3,000 patches, so they spill; with its rows in memory the job would not fit.
std::vector<std::string> SpillingLimit(const v1::SolveOptions& options, uint64_t extra = 64 << 10) {
  const uint64_t limit = Estimate(options, 1) - 1 + extra;
  EXPECT_GT(Estimate(options, 0), limit) << "the rows in memory must not fit";
  return {"--max-memory", std::to_string(limit)};
}

// The options the server's spilled job is compared against: the same, solved in memory
// by gauss_seidel (what auto becomes when rows spill).
v1::SolveOptions AsGaussSeidel(v1::SolveOptions options) {
  options.set_solver("gauss_seidel");
  return options;
}

// The report's matrix.spill says the rows were spilled and read back.
void ExpectSpilled(const std::string& report_json) {
  const nlohmann::json report = nlohmann::json::parse(report_json);
  const nlohmann::json& spill = report["matrix"]["spill"];
  ASSERT_TRUE(spill.is_object()) << report["matrix"].dump();
  EXPECT_GT(spill["spilled_bytes"].get<uint64_t>(), 0u);
  EXPECT_LE(spill["memory_bytes"].get<uint64_t>(), spill["memory_limit"].get<uint64_t>());
  EXPECT_GT(spill["read_passes"].get<int>(), 0);
  EXPECT_EQ(report["solve"]["method"], "gauss_seidel");
}

TEST_F(ServiceSpillTest, JobWhoseRowsDoNotFitRunsSpilledAndEqualsInMemoryGaussSeidel) {
  const v1::SolveOptions options = SmallOptions(3000, "auto");
  StartServer(SpillingLimit(options));
  const std::string sha = UploadCornell();
  v1::Job job;
  const grpc::Status submitted = Submit(options, &job, sha);
  ASSERT_TRUE(submitted.ok()) << submitted.error_message();
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  std::vector<double> served;
  std::string report;
  ASSERT_TRUE(Result(job.job_id(), &served, &report).ok());
  ExpectSpilled(report);
  ExpectBitIdentical(served, InProcess(AsGaussSeidel(options)));
}

TEST_F(ServiceSpillTest, JobThatCannotSpillOrDoesNotFitSpilledIsRefused) {
  const v1::SolveOptions cg = SmallOptions(3000, "cg");
  StartServer(SpillingLimit(cg));
  const std::string sha = UploadCornell();
  v1::Job job;
  grpc::Status s = Submit(cg, &job, sha);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(s.error_message().find("solver cg cannot spill rows to disk"), std::string::npos)
      << s.error_message();

  const v1::SolveOptions gauss_seidel = SmallOptions(3000, "gauss_seidel");
  StartServer({"--max-memory", std::to_string(Estimate(gauss_seidel, 1) - 1)});
  s = Submit(gauss_seidel, &job, UploadCornell());
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(s.error_message().find("even with its rows spilled to disk"), std::string::npos)
      << s.error_message();
}

TEST_F(ServiceSpillTest, KillNineDuringSpilledSolveResumesBitIdentical) {
  v1::SolveOptions options = SmallOptions(3000, "auto");
  options.set_tolerance(1e-6);
  int first_iteration = 0;
  std::string report;
  const std::vector<double> served =
      KillDuringSolveAndResume(*this, options, &first_iteration, &report, SpillingLimit(options));
  EXPECT_GE(first_iteration, 5) << "the restarted solve resumes from its checkpoint";
  ExpectSpilled(report);
  ExpectBitIdentical(served, InProcess(AsGaussSeidel(options)));
}

}  // namespace
}  // namespace radflux
