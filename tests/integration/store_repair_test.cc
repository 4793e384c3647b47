// The job store repairs or refuses what it cannot trust (issue 22): writers of one blob at
// once each rename a whole file of their own into place; a stored scene whose files fail
// their check is marked missing so that an upload of the same bytes writes it again; a data
// directory whose database is gone while scenes or jobs remain refuses to start.
#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_split.h"
#include "server/store/blob_file.h"
#include "tests/integration/radfluxd_path.h"
#include "tests/integration/service_fixture.h"
#include "wire/scene_stream.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;
using testing::kMtl;
using testing::kObj;

class StoreRepairTest : public testing::ServiceFixture {
 public:
  // GetScene of `sha` read to its end (ReadSceneChunks).
  absl::StatusOr<StoredScene> GetScene(const std::string& sha) {
    v1::GetSceneRequest request;
    request.set_sha256(sha);
    auto context = Context();
    auto reader = stub_->GetScene(context.get(), request);
    return ReadSceneChunks(*reader, sha);
  }
};

TEST_F(StoreRepairTest, WritersOfOneBlobAtOnceAllSucceedAndLeaveOneWholeFile) {
  constexpr int kWriters = 20;
  constexpr int kRounds = 5;
  const std::string path = data_dir_ + "/scene.obj.rfb";
  std::string data(1 << 20, '\0');
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<char>((i * 2654435761u) >> 13);
  std::vector<absl::Status> statuses(kWriters * kRounds);
  std::vector<std::thread> writers;
  for (int w = 0; w < kWriters; ++w) {
    writers.emplace_back([&, w] {
      for (int r = 0; r < kRounds; ++r) statuses[w * kRounds + r] = WriteBlobFile(path, data);
    });
  }
  for (std::thread& t : writers) t.join();
  for (const absl::Status& s : statuses) EXPECT_TRUE(s.ok()) << s;
  absl::StatusOr<std::string> read = ReadBlobFile(path);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_TRUE(*read == data);
  std::vector<std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(data_dir_)) {
    files.push_back(e.path().filename().string());
  }
  EXPECT_EQ(files, std::vector<std::string>{"scene.obj.rfb"}) << "no temp file left";
}

TEST_F(StoreRepairTest, CorruptStoredSceneIsMarkedMissingAndAnUploadRepairsIt) {
  StartServer();
  v1::SceneRef ref;
  ASSERT_TRUE(Upload(kObj, kMtl, &ref, SceneContentHash(kObj, kMtl)).ok());
  const std::string obj = data_dir_ + "/scenes/" + ref.sha256() + ".obj.rfb";
  {
    std::fstream file(obj, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(fs::file_size(obj) / 2));
    file.put('\x5a').put('\xa5').put('\x5a');
  }
  const absl::Status corrupt = GetScene(ref.sha256()).status();
  EXPECT_EQ(corrupt.code(), absl::StatusCode::kDataLoss) << corrupt;
  EXPECT_NE(corrupt.message().find("upload it again"), std::string::npos) << corrupt;
  EXPECT_EQ(corrupt.message().find(data_dir_), std::string::npos) << "no server path: " << corrupt;

  v1::SceneRef again;
  ASSERT_TRUE(Upload(kObj, kMtl, &again, SceneContentHash(kObj, kMtl)).ok());
  EXPECT_EQ(again.sha256(), ref.sha256());
  EXPECT_FALSE(again.already_stored()) << "the corrupt scene was stored again";
  const absl::StatusOr<StoredScene> repaired = GetScene(ref.sha256());
  ASSERT_TRUE(repaired.ok()) << repaired.status();
  EXPECT_TRUE(repaired->obj == kObj && repaired->mtl == kMtl);
}

// The temp files of uploads in progress under scenes/ (SceneUpload: "upload.*").
std::vector<std::string> UploadTempFiles(const std::string& data_dir) {
  std::vector<std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(data_dir + "/scenes")) {
    if (e.path().filename().string().starts_with("upload.")) files.push_back(e.path().string());
  }
  return files;
}

// Polls (every 10 ms, for at most 60 s: a bound, not a timing the test relies on) until
// `done()`; returns done().
bool Eventually(const std::function<bool()>& done) {
  for (int i = 0; i < 6000 && !done(); ++i) usleep(10'000);
  return done();
}

// An upload's bytes go to a temp file in the data directory as they arrive (the whole
// upload was held in memory before: no file appeared until it had ended); an upload
// cancelled mid-stream, or cut by kill -9 of the server, leaves no file behind.
TEST_F(StoreRepairTest, AnUploadStreamsToDiskAndOneCutShortLeavesNoFile) {
  StartServer();
  for (const bool kill_server : {false, true}) {
    SCOPED_TRACE(kill_server ? "server killed" : "upload cancelled");
    v1::SceneRef ref;
    auto context = Context();
    auto writer = stub_->UploadScene(context.get(), &ref);
    v1::SceneChunk chunk;
    chunk.mutable_header()->set_name("cornell_box.obj");
    chunk.mutable_header()->set_obj_size(kObj.size());
    chunk.mutable_header()->set_mtl_size(kMtl.size());
    chunk.set_data(kObj.substr(0, kObj.size() / 2));
    ASSERT_TRUE(writer->Write(chunk));
    ASSERT_TRUE(Eventually([&] { return UploadTempFiles(data_dir_).size() == 2; }))
        << "no temp files (OBJ and MTL) while the upload is open";
    if (kill_server) {
      server_->Kill();
      EXPECT_EQ(UploadTempFiles(data_dir_).size(), 2u);
      StartServer();  // removes them before it listens
      EXPECT_EQ(UploadTempFiles(data_dir_), std::vector<std::string>{});
    } else {
      context->TryCancel();
      EXPECT_EQ(writer->Finish().error_code(), grpc::StatusCode::CANCELLED);
      EXPECT_TRUE(Eventually([&] { return UploadTempFiles(data_dir_).empty(); }))
          << UploadTempFiles(data_dir_)[0];
    }
  }
  EXPECT_TRUE(fs::is_empty(data_dir_ + "/scenes")) << "no scene was stored";
}

// A scene uploaded in pieces that straddle its OBJ/MTL boundary gets the content address
// it got when uploads were held in memory (pinned: SHA-256 of "radflux-scene-v1\n71\n" +
// OBJ + MTL), and is stored with exactly its bytes.
TEST_F(StoreRepairTest, AStreamedUploadKeepsItsContentAddress) {
  const std::string obj =
      "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl white\nf 1 2 3 4\n";
  const std::string mtl = "newmtl white\nKd 0.5 0.5 0.5\n";
  const std::string kPinned = "2021ab16334b732ac890633679ba073bc7f8dd76fc71f2fe48d74321189ced19";
  ASSERT_EQ(SceneContentHash(obj, mtl), kPinned);
  StartServer();
  v1::SceneRef ref;
  auto context = Context();
  auto writer = stub_->UploadScene(context.get(), &ref);
  v1::SceneChunk chunk;
  chunk.mutable_header()->set_name("quad.obj");
  chunk.mutable_header()->set_obj_size(obj.size());
  chunk.mutable_header()->set_mtl_size(mtl.size());
  const std::string data = obj + mtl;
  for (size_t at = 0; at < data.size(); at += 7) {  // 71 = 10 * 7 + 1: a chunk straddles
    chunk.set_data(data.substr(at, 7));
    ASSERT_TRUE(writer->Write(chunk));
    chunk.clear_header();
  }
  writer->WritesDone();
  const grpc::Status status = writer->Finish();
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(ref.sha256(), kPinned);
  EXPECT_EQ(ref.faces(), 1u);
  const absl::StatusOr<StoredScene> stored = GetScene(kPinned);
  ASSERT_TRUE(stored.ok()) << stored.status();
  EXPECT_EQ(stored->obj, obj);
  EXPECT_EQ(stored->mtl, mtl);
  EXPECT_EQ(UploadTempFiles(data_dir_), std::vector<std::string>{});
}

// A result file corrupted on disk after it was marked durable is computed again when it is
// asked for (it was only reported, DATA_LOSS): the call answers UNAVAILABLE without the
// server's paths, the job runs again, and its new result is bit-identical to the first.
TEST_F(StoreRepairTest, CorruptResultIsComputedAgainBitIdentical) {
  StartServer();
  const std::string sha = UploadCornell();
  v1::Job job;
  ASSERT_TRUE(Submit(testing::SmallOptions(100, "jacobi"), &job, sha).ok());
  ASSERT_EQ(Watch(job.job_id()).back().state(), v1::JOB_STATE_SUCCEEDED);
  std::vector<double> original;
  ASSERT_TRUE(Result(job.job_id(), &original).ok());
  ASSERT_GT(original.size(), 50u);
  ASSERT_EQ(server_->Stop(), 0);  // the result is read from its file after a restart
  const std::string result = data_dir_ + "/jobs/" + job.job_id() + "/result.rfb";
  {
    std::fstream file(result, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(fs::file_size(result) / 2));
    file.put('\x5a').put('\xa5').put('\x5a');
  }
  StartServer();
  std::vector<double> none;
  const grpc::Status read = Result(job.job_id(), &none);
  EXPECT_EQ(read.error_code(), grpc::StatusCode::UNAVAILABLE) << read.error_message();
  EXPECT_NE(read.error_message().find("being computed again"), std::string::npos)
      << read.error_message();
  EXPECT_EQ(read.error_message().find(data_dir_), std::string::npos) << read.error_message();

  const std::vector<v1::JobEvent> rerun = Watch(job.job_id());
  EXPECT_EQ(rerun.front().state(), v1::JOB_STATE_QUEUED) << rerun.front().message();
  ASSERT_EQ(rerun.back().state(), v1::JOB_STATE_SUCCEEDED) << rerun.back().message();
  std::vector<double> again;
  const grpc::Status reread = Result(job.job_id(), &again);
  ASSERT_TRUE(reread.ok()) << reread.error_message();
  ASSERT_EQ(again.size(), original.size());
  EXPECT_EQ(std::memcmp(again.data(), original.data(), again.size() * sizeof(double)), 0)
      << "the recomputed B differs from the first";
}

// radfluxd's exit status and everything it printed (stdout and stderr), on `data_dir`.
// `timeout` ends a server that starts after all, which then fails the test (exit 124).
std::pair<int, std::string> RunRadfluxd(const std::string& data_dir) {
  const std::string command = "timeout 60 " + testing::RadfluxdPath() +
                              " --listen 127.0.0.1:0 --data-dir '" + data_dir + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  for (size_t n; pipe && (n = fread(buffer, 1, sizeof(buffer), pipe)) > 0;)
    output.append(buffer, n);
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

TEST_F(StoreRepairTest, DataDirWithoutItsDatabaseRefusesToStartAndSaysHowToRecover) {
  StartServer();
  UploadCornell();
  ASSERT_EQ(server_->Stop(), 0);
  ASSERT_TRUE(fs::remove(data_dir_ + "/radflux.db"));

  const auto [exit_code, output] = RunRadfluxd(data_dir_);
  EXPECT_NE(exit_code, 0) << output;
  EXPECT_NE(exit_code, 124) << "it started: " << output;
  const std::vector<std::string> lines = absl::StrSplit(output, '\n', absl::SkipEmpty());
  EXPECT_EQ(lines.size(), 1u) << output;
  EXPECT_NE(output.find("no database"), std::string::npos) << output;
  EXPECT_NE(output.find("restore radflux.db"), std::string::npos) << output;
  EXPECT_NE(output.find("move " + data_dir_ + " away"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(data_dir_ + "/radflux.db")) << "no empty database was created";

  // A fresh directory (nothing to orphan) still starts.
  fs::remove_all(data_dir_);
  StartServer();
  EXPECT_EQ(server_->Stop(), 0);
}

}  // namespace
}  // namespace radflux
