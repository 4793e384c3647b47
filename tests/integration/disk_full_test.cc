// A disk that fills (issue 22): the job store's data directory on a tmpfs of a few MiB
// (tiny_filesystem.h), filled to the last byte by a ballast file while a job builds its
// rows. The job ends FAILED with a plain "disk full writing ..." message, never SUCCEEDED;
// its partial files are gone; the server keeps answering; the FAILED state is written even
// when SQLite itself finds the disk full (the store's space reserve) and survives a restart;
// once space is back a small job succeeds with the exact result. A job that cannot fit the
// disk at all is refused at submit, and so is one that does not fit beside the disk the
// unfinished jobs may still write, also when both are submitted at once.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "server/store/job_store.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"
#include "tests/integration/tiny_filesystem.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;
using testing::SmallOptions;
using testing::TinyFilesystem;

// Every file under `dir` (recursively) whose name contains `part`.
std::vector<std::string> FilesNamed(const std::string& dir, const std::string& part) {
  std::vector<std::string> found;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().filename().string().find(part) != std::string::npos) {
      found.push_back(e.path().string());
    }
  }
  return found;
}

class DiskFullTest : public testing::ServiceFixture {};

TEST_F(DiskFullTest, JobOnAFillingDiskFailsCleanlyAndTheServerGoesOn) {
  TinyFilesystem disk(data_dir_, 16 << 20);
  ASSERT_TRUE(disk.ok());
  // Row blocks are checkpointed one by one, 20 ms apart: the disk fills mid-rows.
  StartServer({"--checkpoint-seconds", "0", "--testing-block-delay-ms", "20"});
  const std::string sha = UploadCornell();
  v1::Job big;
  ASSERT_TRUE(Submit(SmallOptions(2000, "jacobi"), &big, sha).ok());
  Watch(big.job_id(), [](const v1::JobEvent& e) {
    return e.phase() == v1::PHASE_ROWS && e.progress().rows_done() > 0;
  });
  disk.Fill();
  const std::vector<v1::JobEvent> events = Watch(big.job_id());
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().state(), v1::JOB_STATE_FAILED) << events.back().message();
  EXPECT_NE(events.back().message().find("disk full writing "), std::string::npos)
      << events.back().message();
  EXPECT_NE(events.back().message().find(data_dir_), std::string::npos) << "names the path";

  // Reads are served on the full disk, and the state is stored, not only published.
  v1::GetJobRequest get;
  get.set_job_id(big.job_id());
  v1::Job stored;
  ASSERT_TRUE(stub_->GetJob(Context().get(), get, &stored).ok());
  EXPECT_EQ(stored.state(), v1::JOB_STATE_FAILED);
  EXPECT_EQ(stored.message(), events.back().message());
  std::vector<double> none;
  EXPECT_EQ(Result(big.job_id(), &none).error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  // No partial files: no row blocks, checkpoint or result of the job, no temp file anywhere.
  EXPECT_TRUE(FilesNamed(data_dir_ + "/jobs/" + big.job_id(), "").empty());
  EXPECT_TRUE(FilesNamed(data_dir_, ".tmp").empty());

  // While the disk stays full, a submit is refused as such (no room for its estimate or for
  // the space reserve; it was INTERNAL) or its job fails the same way; never a success.
  disk.Fill();
  v1::Job refused;
  const grpc::Status status = Submit(SmallOptions(100, "jacobi"), &refused, sha);
  if (status.ok()) {
    EXPECT_EQ(Watch(refused.job_id()).back().state(), v1::JOB_STATE_FAILED);
  } else {
    EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
    EXPECT_NE(status.error_message().find("disk"), std::string::npos) << status.error_message();
  }

  // Space back: a small job succeeds with the exact result, and a restart keeps the failed
  // job FAILED (it used to be re-run into the same wall at every start).
  disk.Drain();
  const v1::SolveOptions small = SmallOptions(100, "jacobi");
  v1::Job after;
  ASSERT_TRUE(Submit(small, &after, sha).ok());
  EXPECT_EQ(Watch(after.job_id()).back().state(), v1::JOB_STATE_SUCCEEDED);
  std::vector<double> served;
  ASSERT_TRUE(Result(after.job_id(), &served).ok());
  testing::ExpectBitIdentical(served, testing::InProcess(small));
  server_->Stop();
  StartServer();
  ASSERT_TRUE(stub_->GetJob(Context().get(), get, &stored).ok());
  EXPECT_EQ(stored.state(), v1::JOB_STATE_FAILED);
}

// A job whose disk estimate (rows, checkpoint, result) exceeds the data directory's free
// space is refused at submit, before any work, naming both; a job that fits is taken.
TEST_F(DiskFullTest, JobThatCannotFitTheDiskIsRefusedAtSubmit) {
  TinyFilesystem disk(data_dir_, 16 << 20);
  ASSERT_TRUE(disk.ok());
  StartServer();
  const std::string sha = UploadCornell();
  v1::SolveOptions huge = SmallOptions(5000, "jacobi");
  huge.set_rays(4096);  // up to 4160 entries in each of 5000 rows: far beyond 16 MiB
  v1::Job job;
  const grpc::Status status = Submit(huge, &job, sha);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_NE(status.error_message().find("MiB of disk"), std::string::npos) << status.error_message();
  EXPECT_NE(status.error_message().find(data_dir_), std::string::npos) << status.error_message();
  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &job, sha).ok());
  EXPECT_EQ(Watch(job.job_id()).back().state(), v1::JOB_STATE_SUCCEEDED);
}

// The disk an unfinished job may still write is held for it: a second job that would fit
// the free space alone, but not beside the first's estimate, is refused until the first
// ends (both were taken, and could fill the disk between them).
TEST_F(DiskFullTest, UnfinishedJobsKeepTheirDiskEstimateFromLaterSubmits) {
  TinyFilesystem disk(data_dir_, 8 << 20);  // ~6.8 MiB free beside the reserve and database
  ASSERT_TRUE(disk.ok());
  // The first job writes nothing while the test runs: its blocks take 2 s each, and none is
  // checkpointed before 16 MiB of them wait.
  StartServer({"--testing-block-delay-ms", "2000", "--checkpoint-seconds", "1000"});
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(1200, "jacobi");  // ~4 MiB of disk
  v1::Job first, second;
  ASSERT_TRUE(Submit(options, &first, sha).ok());
  const grpc::Status status = Submit(options, &second, sha);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  // The first job has written nothing, so all of its estimate (the same as the second's
  // need: same options) is still held for it.
  const std::string& message = status.error_message();
  const std::string need = "would need up to ", held = "the unfinished jobs may still write ";
  const size_t need_at = message.find(need), held_at = message.find(held);
  ASSERT_NE(need_at, std::string::npos) << message;
  ASSERT_NE(held_at, std::string::npos) << message;
  const std::string need_mib = message.substr(need_at + need.size(), 4);
  EXPECT_EQ(message.substr(held_at + held.size(), 4), need_mib) << message;
  EXPECT_GT(std::stod(need_mib), 2.0) << message;  // the estimate of ~1,100 patches, not 0

  v1::CancelJobRequest cancel;
  cancel.set_job_id(first.job_id());
  ASSERT_TRUE(stub_->CancelJob(Context().get(), cancel, &first).ok());
  EXPECT_EQ(Watch(first.job_id()).back().state(), v1::JOB_STATE_CANCELLED);
  EXPECT_TRUE(Submit(options, &second, sha).ok());
}

// Two submits at once, each fitting the free space alone but not both: one is taken and
// the other refused. The disk check and the insert that holds the job's estimate are one
// step under the submit lock; --testing-submit-delay-ms sleeps inside that step, so with the
// check outside it (as before) both submits passed their checks before either was held.
TEST_F(DiskFullTest, TwoSubmitsAtOnceCannotBothTakeTheRoomOfOne) {
  TinyFilesystem disk(data_dir_, 8 << 20);  // ~6.8 MiB free beside the reserve and database
  ASSERT_TRUE(disk.ok());
  StartServer({"--testing-block-delay-ms", "2000", "--checkpoint-seconds", "1000",
               "--testing-submit-delay-ms", "1000"});
  const std::string sha = UploadCornell();
  const v1::SolveOptions options = SmallOptions(1200, "jacobi");  // ~4 MiB of disk
  v1::Job jobs[2];
  grpc::Status statuses[2];
  std::vector<std::thread> submits;
  for (int k = 0; k < 2; ++k) {
    submits.emplace_back([&, k] { statuses[k] = Submit(options, &jobs[k], sha); });
  }
  for (std::thread& t : submits) t.join();
  EXPECT_NE(statuses[0].ok(), statuses[1].ok())
      << statuses[0].error_message() << " / " << statuses[1].error_message();
  const grpc::Status& refused = statuses[0].ok() ? statuses[1] : statuses[0];
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << refused.error_message();
  EXPECT_NE(refused.error_message().find("would need up to"), std::string::npos)
      << refused.error_message();
}

// SQLite itself finds the disk full: a RUNNING update is refused with a plain message,
// and the job's end (FAILED) is still written, in the space the store kept for it.
TEST_F(DiskFullTest, TheEndOfAJobIsWrittenOnAFullDisk) {
  TinyFilesystem disk(data_dir_, 8 << 20);
  ASSERT_TRUE(disk.ok());
  absl::StatusOr<std::unique_ptr<JobStore>> store = JobStore::Open(data_dir_);
  ASSERT_TRUE(store.ok()) << store.status();
  v1::Job job;
  job.set_job_id("job-1");
  job.set_scene_sha256("abc");
  job.set_state(v1::JOB_STATE_RUNNING);
  ASSERT_TRUE((*store)->CreateJob(job, /*request_hash=*/"").ok());
  disk.Fill();

  job.set_message(std::string(2 << 20, 'r'));  // far more than the log's slack
  const absl::Status running = (*store)->UpdateJob(job);
  EXPECT_EQ(running.code(), absl::StatusCode::kResourceExhausted) << running;
  EXPECT_NE(running.message().find("disk full writing the job's state at " + data_dir_ +
                                   "/radflux.db"),
            std::string::npos)
      << running;

  job.set_state(v1::JOB_STATE_FAILED);
  job.set_message("disk full: " + std::string(100 << 10, 'f'));  // within the reserve
  ASSERT_TRUE((*store)->UpdateJob(job).ok());
  absl::StatusOr<v1::Job> read = (*store)->GetJob("job-1");
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->state(), v1::JOB_STATE_FAILED);
  EXPECT_EQ(read->message(), job.message());

  // While the reserve is spent the store refuses new work; with space back it holds it again.
  EXPECT_EQ((*store)->EnsureSpaceReserve().code(), absl::StatusCode::kResourceExhausted);
  disk.Drain();
  EXPECT_TRUE((*store)->EnsureSpaceReserve().ok());
}

}  // namespace
}  // namespace radflux
