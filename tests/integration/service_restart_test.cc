// Integration tests of radfluxd's restarts: kill -9 during rows and during the solve, and a
// finished job whose result an OS crash lost; each test starts its own server on a port the
// server picks, with a fresh data directory, and restarts it on the same directory.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "radflux/v1/radiosity.grpc.pb.h"
#include "server/store/blob_file.h"
#include "server/store/stored_codec.h"
#include "solver/pipeline.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;
using testing::ExpectBitIdentical;
using testing::InProcess;
using testing::KillDuringSolveAndResume;
using testing::SmallOptions;

class ServiceRestartTest : public testing::ServiceFixture {};

TEST_F(ServiceRestartTest, KillNineDuringRowsThenRestartResumesWithIdenticalResult) {
  // Row blocks stored as soon as they are built, and slow enough to kill the job mid-rows.
  StartServer({"--checkpoint-seconds", "0", "--testing-block-delay-ms", "20"});
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(1200, "jacobi");
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha).ok());
  Watch(job.job_id(), [](const v1::JobEvent& e) { return e.progress().rows_done() >= 64; });
  // Blocks are stored behind the row builders: kill once the first one is on disk.
  const auto stored_blocks = [&] {
    size_t blocks = 0;
    for (const auto& f : fs::directory_iterator(data_dir_ + "/jobs/" + job.job_id())) {
      blocks += f.path().filename().string().rfind("rows_", 0) == 0;
    }
    return blocks;
  };
  while (stored_blocks() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  server_->Kill();
  EXPECT_GT(stored_blocks(), 0u) << "row blocks survive kill -9";

  StartServer();
  v1::ListJobsRequest list_request;
  v1::ListJobsResponse list;
  ASSERT_TRUE(stub_->ListJobs(Context().get(), list_request, &list).ok());
  ASSERT_EQ(list.jobs_size(), 1);
  EXPECT_EQ(list.jobs(0).job_id(), job.job_id());
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_FALSE(events.empty());
  ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  std::vector<double> served;
  ASSERT_TRUE(Result(job.job_id(), &served).ok());
  ExpectBitIdentical(served, InProcess(options));

  // A finished job still returns its result after another restart.
  server_->Stop();
  StartServer();
  std::vector<double> again;
  ASSERT_TRUE(Result(job.job_id(), &again).ok());
  ExpectBitIdentical(again, served);
}

// The row-block checkpoint files of a job (rows_<first block>.rfb, complete ones only).
std::vector<fs::path> RowFiles(const std::string& job_dir) {
  std::vector<fs::path> files;
  for (const auto& f : fs::directory_iterator(job_dir)) {
    const std::string name = f.path().filename().string();
    if (name.rfind("rows_", 0) == 0 && f.path().extension() == ".rfb") files.push_back(f.path());
  }
  return files;
}

// The rows done reported by the first row-progress event of `events` (0 if none).
int64_t FirstRowsDone(const std::vector<v1::JobEvent>& events) {
  for (const v1::JobEvent& e : events) {
    if (e.phase() == v1::PHASE_ROWS && e.progress().rows_done() > 0)
      return e.progress().rows_done();
  }
  return 0;
}

TEST_F(ServiceRestartTest, KillNineBetweenGroupedRowCheckpointsResumesFromThemBitIdentical) {
  // 75 blocks of 16 rows, each held 50 ms after it is built on 2 threads: the rows take about
  // 2 s and are checkpointed every 0.5 s, several blocks per file.
  StartServer({"--checkpoint-seconds", "0.5", "--testing-block-delay-ms", "50"});
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(1200, "jacobi");
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha).ok());
  const std::string job_dir = data_dir_ + "/jobs/" + job.job_id();
  Watch(job.job_id(), [](const v1::JobEvent& e) { return e.phase() == v1::PHASE_ROWS; });
  while (RowFiles(job_dir).empty()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  server_->Kill();
  size_t stored = 0;
  for (const fs::path& file : RowFiles(job_dir)) {
    absl::StatusOr<std::string> bytes = ReadBlobFile(file.string());
    ASSERT_TRUE(bytes.ok()) << bytes.status();
    absl::StatusOr<std::vector<StoredRowBlock>> group = DecodeRowBlockGroup(*bytes);
    ASSERT_TRUE(group.ok()) << group.status();
    stored += group->size();
  }
  EXPECT_GT(stored, RowFiles(job_dir).size()) << "a checkpoint stores several blocks in a file";
  EXPECT_LT(stored, 75u) << "killed mid rows";

  StartServer();
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  EXPECT_GE(FirstRowsDone(events), static_cast<int64_t>(16 * stored))
      << "the restarted job reuses the checkpointed blocks";
  std::vector<double> served;
  ASSERT_TRUE(Result(job.job_id(), &served).ok());
  ExpectBitIdentical(served, InProcess(options));
}

TEST_F(ServiceRestartTest, KillNineBeforeTheFirstCheckpointRebuildsAndEndsBitIdentical) {
  // A checkpoint interval longer than the job: nothing is stored when the kill lands, the
  // restarted server builds every row again and ends with the same result.
  StartServer({"--checkpoint-seconds", "3600", "--testing-block-delay-ms", "20"});
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(1200, "gauss_seidel");
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha).ok());
  const std::string job_dir = data_dir_ + "/jobs/" + job.job_id();
  Watch(job.job_id(), [](const v1::JobEvent& e) { return e.progress().rows_done() >= 320; });
  server_->Kill();
  EXPECT_TRUE(RowFiles(job_dir).empty()) << "no checkpoint before the interval has passed";

  StartServer();
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  EXPECT_LE(FirstRowsDone(events), 16 * 2) << "nothing was reused";
  std::vector<double> served;
  ASSERT_TRUE(Result(job.job_id(), &served).ok());
  ExpectBitIdentical(served, InProcess(options));
}

TEST_F(ServiceRestartTest, KillNineDuringSouthwellSolveResumesBitIdentical) {
  v1::SolveOptions options = SmallOptions(1200, "southwell");
  options.set_tolerance(1e-5);
  int first_iteration = 0;
  std::string report;
  const std::vector<double> served =
      KillDuringSolveAndResume(*this, options, &first_iteration, &report);
  EXPECT_GE(first_iteration, 5) << "the restarted solve resumes from its checkpoint";
  // Southwell's checkpoint is its whole state (B and the unshot radiosity): the resumed
  // run computes exactly what an uninterrupted run computes.
  ExpectBitIdentical(served, InProcess(options));
}

TEST_F(ServiceRestartTest, KillNineDuringCgSolveResumesWithinTolerance) {
  constexpr double kTolerance = 1e-6;
  v1::SolveOptions options = SmallOptions(1200, "cg");
  options.set_tolerance(kTolerance);
  int first_iteration = 0;
  std::string report;
  const std::vector<double> served =
      KillDuringSolveAndResume(*this, options, &first_iteration, &report);
  EXPECT_GE(first_iteration, 5) << "the restarted solve resumes from its checkpoint";
  // CG warm-starts from the checkpointed B (its Krylov space restarts), so the result is
  // in general not bit-identical. Invariants: the resumed result converged (relative residual <=
  // tolerance, as the report says), and it differs from the uninterrupted run by at most
  // 10 * tolerance relative to the largest B of its band, per patch and band.
  const nlohmann::json json = nlohmann::json::parse(report);
  EXPECT_TRUE(json["solve"]["converged"].get<bool>());
  EXPECT_LE(json["solve"]["residual"].get<double>(), kTolerance);
  const std::vector<double> reference = InProcess(options);
  ASSERT_EQ(served.size(), reference.size());
  std::array<double, 3> band_max{};
  for (size_t i = 0; i < reference.size(); ++i)
    band_max[i % 3] = std::max(band_max[i % 3], std::abs(reference[i]));
  double worst = 0;
  for (size_t i = 0; i < reference.size(); ++i)
    worst = std::max(worst, std::abs(served[i] - reference[i]) / band_max[i % 3]);
  // The result may still be bit-identical: CG restarts a lane from the true residual
  // whenever the rows are not reciprocal enough (defect correction), and a checkpoint taken
  // at such a restart resumes on exactly the uninterrupted path. first_iteration >= 5 above
  // is what proves the warm start.
  EXPECT_LE(worst, 10 * kTolerance);
}

// What an OS crash can leave of a finished job: its SUCCEEDED commit durable, its result
// file's fsync (which runs beside that commit's) cut short, and the mark that the result is
// durable (written without an fsync after both) lost. Simulated here: the mark is deleted
// and the result file removed (one job) or corrupted (another). The restarted server finds
// both results unreadable, computes them again, and serves the same B as before.
TEST_F(ServiceRestartTest, SucceededJobWithLostResultComputesItAgainAfterRestart) {
  StartServer();
  const std::string sha = UploadCornell();
  const std::array<v1::SolveOptions, 2> options = {SmallOptions(600, "cg"),
                                                   SmallOptions(600, "gauss_seidel")};
  std::array<std::string, 2> ids;
  std::array<std::vector<double>, 2> first;
  for (size_t k = 0; k < 2; ++k) {
    v1::Job job;
    ASSERT_TRUE(Submit(options[k], &job, sha).ok());
    ids[k] = job.job_id();
    const std::vector<v1::JobEvent> events = Watch(ids[k]);
    ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
    ASSERT_TRUE(Result(ids[k], &first[k]).ok());
  }
  server_->Stop();

  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((data_dir_ + "/radflux.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "DELETE FROM durable_results", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  const std::string lost = data_dir_ + "/jobs/" + ids[0] + "/result.rfb";
  const std::string corrupt = data_dir_ + "/jobs/" + ids[1] + "/result.rfb";
  ASSERT_TRUE(fs::remove(lost));
  {
    std::fstream file(corrupt, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(fs::file_size(corrupt) / 2));
    file.put('\x5a').put('\xa5').put('\x5a');
  }
  ASSERT_EQ(ReadBlobFile(corrupt).status().code(), absl::StatusCode::kDataLoss);

  StartServer();
  for (size_t k = 0; k < 2; ++k) {
    const std::vector<v1::JobEvent> events = Watch(ids[k]);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.front().state(), v1::JOB_STATE_QUEUED) << "computed again";
    ASSERT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
    std::vector<double> again;
    ASSERT_TRUE(Result(ids[k], &again).ok());
    ExpectBitIdentical(again, first[k]);
  }

  // Verified and marked: another restart serves both results without computing them again.
  server_->Stop();
  StartServer();
  for (size_t k = 0; k < 2; ++k) {
    const std::vector<v1::JobEvent> events = Watch(ids[k]);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events.front().state(), v1::JOB_STATE_SUCCEEDED);
    std::vector<double> again;
    ASSERT_TRUE(Result(ids[k], &again).ok());
    ExpectBitIdentical(again, first[k]);
  }
}

}  // namespace
}  // namespace radflux
