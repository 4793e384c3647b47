// Principals (issue 22, "one token for everyone"): radfluxd --tokens-file maps tokens to named
// principals; a principal sees, watches, cancels and fetches only its own jobs and scenes
// (another's are NOT_FOUND, word for word as a job that does not exist), an admin sees all;
// per-principal limits refuse submits; request ids are scoped to the principal; --token alone
// still works, and a database from before principals gives its rows to that principal.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <stdio.h>
#include <sys/wait.h>

#include <fstream>

#include "tests/integration/certificates.h"
#include "tests/integration/radfluxd_path.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"
#include "wire/scene_hash.h"

namespace radflux {
namespace {

using testing::kMtl;
using testing::kObj;
using testing::SmallOptions;

class PrincipalsTest : public testing::ServiceFixture {
 public:
  // Writes `text` as the tokens file and returns its path.
  std::string TokensFile(const std::string& text) {
    const std::string path = data_dir_ + "/tokens.txt";
    std::ofstream(path) << text;
    return path;
  }

  // The calls that follow carry `token`.
  void As(const std::string& token) { token_ = token; }

  grpc::Status GetJob(const std::string& job_id, v1::Job* job = nullptr) {
    v1::GetJobRequest request;
    request.set_job_id(job_id);
    v1::Job ignored;
    return stub_->GetJob(Context().get(), request, job ? job : &ignored);
  }
  grpc::Status Cancel(const std::string& job_id) {
    v1::CancelJobRequest request;
    request.set_job_id(job_id);
    v1::Job job;
    return stub_->CancelJob(Context().get(), request, &job);
  }
  // The ids of the jobs ListJobs shows the caller.
  std::vector<std::string> ListedIds() {
    v1::ListJobsResponse list;
    EXPECT_TRUE(stub_->ListJobs(Context().get(), {}, &list).ok());
    std::vector<std::string> ids;
    for (const v1::Job& job : list.jobs()) ids.push_back(job.job_id());
    return ids;
  }
  // The status a WatchJob stream ends with (after reading all it sends).
  grpc::Status WatchStatus(const std::string& job_id) {
    v1::WatchJobRequest request;
    request.set_job_id(job_id);
    auto context = Context();
    auto reader = stub_->WatchJob(context.get(), request);
    for (v1::JobEvent event; reader->Read(&event);) {
    }
    return reader->Finish();
  }
  grpc::Status GetScene(const std::string& sha) {
    v1::GetSceneRequest request;
    request.set_sha256(sha);
    auto context = Context();
    auto reader = stub_->GetScene(context.get(), request);
    for (v1::SceneChunk chunk; reader->Read(&chunk);) {
    }
    return reader->Finish();
  }
  // Watches a job to its end; its final state.
  v1::JobState FinalState(const std::string& job_id, std::string* message = nullptr) {
    const std::vector<v1::JobEvent> events = Watch(job_id);
    if (events.empty()) return v1::JOB_STATE_UNSPECIFIED;
    if (message) *message = events.back().message();
    return events.back().state();
  }
};

// Expects NOT_FOUND with exactly the message of a job id that does not exist.
void ExpectNotFoundAsMissing(const grpc::Status& status, const std::string& job_id) {
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND) << status.error_message();
  EXPECT_EQ(status.error_message(), "no job " + job_id);
}

TEST_F(PrincipalsTest, PrincipalsSeeOnlyTheirOwnJobsAndScenesAndAnAdminSeesAll) {
  StartServer({"--tokens-file", TokensFile("# principals of the test\n"
                                           "alice tok-alice\n"
                                           "\n"
                                           "bob   tok-bob     # a comment\n"
                                           "ops   tok-ops admin\n")});
  As("tok-alice");
  const std::string sha = UploadCornell();
  v1::Job job;
  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &job, sha).ok());
  EXPECT_EQ(job.owner(), "alice");
  ASSERT_EQ(FinalState(job.job_id()), v1::JOB_STATE_SUCCEEDED);

  // bob: alice's job and scene do not exist for him, in every call.
  As("tok-bob");
  ExpectNotFoundAsMissing(GetJob(job.job_id()), job.job_id());
  ExpectNotFoundAsMissing(Cancel(job.job_id()), job.job_id());
  ExpectNotFoundAsMissing(WatchStatus(job.job_id()), job.job_id());
  std::vector<double> b;
  ExpectNotFoundAsMissing(Result(job.job_id(), &b), job.job_id());
  EXPECT_TRUE(b.empty());
  ExpectNotFoundAsMissing(GetJob("job-0000000000000000"), "job-0000000000000000");
  EXPECT_TRUE(ListedIds().empty());
  EXPECT_EQ(GetScene(sha).error_code(), grpc::StatusCode::NOT_FOUND);
  v1::Job refused;
  EXPECT_EQ(Submit(SmallOptions(100, "jacobi"), &refused, sha).error_code(),
            grpc::StatusCode::NOT_FOUND);
  // His own upload of the same bytes is his first (whether alice has them stays unsaid).
  v1::SceneRef ref;
  ASSERT_TRUE(Upload(kObj, kMtl, &ref, sha).ok());
  EXPECT_FALSE(ref.already_stored());
  EXPECT_TRUE(GetScene(sha).ok());
  v1::Job bobs;
  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &bobs, sha).ok());
  EXPECT_EQ(ListedIds(), std::vector<std::string>{bobs.job_id()});

  // alice sees her job only, and still everything of it.
  As("tok-alice");
  EXPECT_EQ(ListedIds(), std::vector<std::string>{job.job_id()});
  ExpectNotFoundAsMissing(GetJob(bobs.job_id()), bobs.job_id());
  b.clear();
  EXPECT_TRUE(Result(job.job_id(), &b).ok());
  EXPECT_FALSE(b.empty());

  // The admin sees both, with their owners, and may cancel bob's.
  As("tok-ops");
  EXPECT_EQ(ListedIds(), (std::vector<std::string>{bobs.job_id(), job.job_id()}));
  v1::Job seen;
  ASSERT_TRUE(GetJob(job.job_id(), &seen).ok());
  EXPECT_EQ(seen.owner(), "alice");
  EXPECT_TRUE(GetScene(sha).ok());
  EXPECT_TRUE(Cancel(bobs.job_id()).ok());

  // No token, or one of nobody: UNAUTHENTICATED.
  As("");
  EXPECT_EQ(GetJob(job.job_id()).error_code(), grpc::StatusCode::UNAUTHENTICATED);
  As("tok-mallory");
  EXPECT_EQ(GetJob(job.job_id()).error_code(), grpc::StatusCode::UNAUTHENTICATED);
}

TEST_F(PrincipalsTest, LimitsRefuseSubmitsNamingTheLimitAndThePrincipal) {
  // --solve-delay-ms keeps carol's first job unfinished while she submits again.
  StartServer({"--solve-delay-ms", "300", "--principal-running-jobs", "1", "--tokens-file",
               TokensFile("carol tok-carol patches=150\n"
                          "dave tok-dave running_jobs=0 cpu_seconds=0.2\n")});
  As("tok-carol");
  const std::string sha = UploadCornell();
  v1::Job job;
  grpc::Status s = Submit(SmallOptions(400, "jacobi"), &job, sha);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << s.error_message();
  EXPECT_NE(s.error_message().find("principal 'carol'"), std::string::npos) << s.error_message();
  EXPECT_NE(s.error_message().find("patches"), std::string::npos) << s.error_message();

  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &job, sha).ok());
  v1::Job second;
  s = Submit(SmallOptions(100, "gauss_seidel"), &second, sha);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << s.error_message();
  EXPECT_NE(s.error_message().find("principal 'carol'"), std::string::npos) << s.error_message();
  EXPECT_NE(s.error_message().find("running_jobs is 1"), std::string::npos) << s.error_message();
  // Once her job ends, she may submit again.
  ASSERT_TRUE(Cancel(job.job_id()).ok());
  EXPECT_EQ(FinalState(job.job_id()), v1::JOB_STATE_CANCELLED);
  ASSERT_TRUE(Submit(SmallOptions(100, "gauss_seidel"), &second, sha).ok());
  ASSERT_TRUE(Cancel(second.job_id()).ok());  // out of dave's way (one job runs at a time)

  // dave's line lifts the running jobs limit; his cpu_seconds (0.2 s = 0.1 s of the job's
  // 2 threads) ends a job whose solve sleeps 0.3 s an iteration.
  As("tok-dave");
  ASSERT_EQ(UploadCornell(), sha);
  v1::Job daves[2];
  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &daves[0], sha).ok());
  ASSERT_TRUE(Submit(SmallOptions(100, "gauss_seidel"), &daves[1], sha).ok());
  std::string message;
  EXPECT_EQ(FinalState(daves[0].job_id(), &message), v1::JOB_STATE_FAILED);
  EXPECT_NE(message.find("cpu_seconds limit of principal 'dave'"), std::string::npos) << message;
}

TEST_F(PrincipalsTest, RequestIdsAreBoundedCheckedAndScopedToThePrincipal) {
  StartServer({"--tokens-file", TokensFile("alice tok-alice\nbob tok-bob\n")});
  const v1::SolveOptions options = SmallOptions(100, "jacobi");
  As("tok-alice");
  const std::string sha = UploadCornell();
  v1::SceneRef other;  // another scene: other bytes
  ASSERT_TRUE(Upload(kObj, kMtl + "# another scene\n", &other).ok());
  ASSERT_NE(other.sha256(), sha);

  v1::Job first, again, refused;
  ASSERT_TRUE(Submit(options, &first, sha, "r-1").ok());
  ASSERT_TRUE(Submit(options, &again, sha, "r-1").ok());
  EXPECT_EQ(again.job_id(), first.job_id());
  const grpc::Status s = Submit(options, &refused, other.sha256(), "r-1");
  EXPECT_EQ(s.error_code(), grpc::StatusCode::FAILED_PRECONDITION) << s.error_message();
  EXPECT_NE(s.error_message().find("\"r-1\""), std::string::npos) << s.error_message();
  EXPECT_TRUE(refused.job_id().empty());
  EXPECT_EQ(Submit(options, &refused, sha, std::string(129, 'r')).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);

  // bob's "r-1" is his own: a job of his, not alice's, and not refused.
  As("tok-bob");
  ASSERT_EQ(UploadCornell(), sha);
  v1::Job bobs;
  ASSERT_TRUE(Submit(options, &bobs, sha, "r-1").ok());
  EXPECT_NE(bobs.job_id(), first.job_id());
  EXPECT_EQ(bobs.owner(), "bob");
  v1::Job bobs_again;
  ASSERT_TRUE(Submit(options, &bobs_again, sha, "r-1").ok());
  EXPECT_EQ(bobs_again.job_id(), bobs.job_id());
}

// The single --token of before is the principal "default", an admin: it works alone, and
// beside a tokens file sees the file's principals' jobs.
TEST_F(PrincipalsTest, TheSingleTokenStillWorksAndIsTheDefaultAdmin) {
  StartServer({"--token", "s3cret", "--tokens-file", TokensFile("alice tok-alice\n")});
  As("tok-alice");
  const std::string sha = UploadCornell();
  v1::Job alices;
  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &alices, sha).ok());
  As("s3cret");
  v1::Job own;
  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &own, sha).ok());
  EXPECT_EQ(own.owner(), "default");
  EXPECT_EQ(ListedIds(), (std::vector<std::string>{own.job_id(), alices.job_id()}));
  As("tok-alice");
  EXPECT_EQ(ListedIds(), std::vector<std::string>{alices.job_id()});
}

// A database written before principals: its jobs become the default principal's (seen by
// --token, not by a file's principal), and their request ids still tell a retry from reuse.
TEST_F(PrincipalsTest, JobsOfADatabaseFromBeforePrincipalsAreTheDefaultPrincipals) {
  const v1::SolveOptions options = SmallOptions(100, "jacobi");
  v1::Job old;
  old.set_job_id("job-00000000000000aa");
  old.set_scene_sha256(SceneContentHash(kObj, kMtl));
  *old.mutable_options() = options;
  old.set_state(v1::JOB_STATE_FAILED);
  old.set_message("from an old server");
  old.set_request_id("old-1");
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((data_dir_ + "/radflux.db").c_str(), &db), SQLITE_OK);
    const std::string v0 =  // the schema before principals (store_schema.cc, version 0)
        "CREATE TABLE jobs(seq INTEGER PRIMARY KEY AUTOINCREMENT, job_id TEXT UNIQUE NOT NULL,"
        " request_id TEXT UNIQUE, scene_sha256 TEXT NOT NULL, state INTEGER NOT NULL,"
        " job BLOB NOT NULL);";
    ASSERT_EQ(sqlite3_exec(db, v0.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_stmt* st = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db,
                                 "INSERT INTO jobs(job_id, request_id, scene_sha256, state, job) "
                                 "VALUES(?, ?, ?, ?, ?)",
                                 -1, &st, nullptr),
              SQLITE_OK);
    const std::string blob = old.SerializeAsString();
    sqlite3_bind_text(st, 1, old.job_id().c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 2, old.request_id().c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 3, old.scene_sha256().c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_int(st, 4, old.state());
    sqlite3_bind_blob(st, 5, blob.data(), static_cast<int>(blob.size()), SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(st), SQLITE_DONE);
    sqlite3_finalize(st);
    sqlite3_close(db);
  }
  StartServer({"--token", "s3cret", "--tokens-file", TokensFile("alice tok-alice\n")});
  As("tok-alice");
  ExpectNotFoundAsMissing(GetJob(old.job_id()), old.job_id());
  As("s3cret");
  v1::Job seen;
  ASSERT_TRUE(GetJob(old.job_id(), &seen).ok());
  EXPECT_EQ(seen.owner(), "default");
  EXPECT_EQ(seen.message(), "from an old server");
  v1::Job retry;
  ASSERT_TRUE(Submit(options, &retry, old.scene_sha256(), "old-1").ok());
  EXPECT_EQ(retry.job_id(), old.job_id());
  v1::SolveOptions other = options;
  other.set_rays(64);
  EXPECT_EQ(Submit(other, &retry, old.scene_sha256(), "old-1").error_code(),
            grpc::StatusCode::FAILED_PRECONDITION);
}

// With mutual TLS, a client certificate's CN names a principal of the tokens file (TOKEN "-":
// by certificate only); a bearer token still decides when a call carries one.
TEST_F(PrincipalsTest, AClientCertificatesCnNamesItsPrincipal) {
  testing::Certificates certs(data_dir_);
  ASSERT_TRUE(certs.MakeCa("server_ca"));
  ASSERT_TRUE(certs.MakeSigned("server", "server_ca", "DNS:localhost,IP:127.0.0.1"));
  ASSERT_TRUE(certs.MakeCa("client_ca"));
  for (const char* cn : {"alice", "bob", "nobody"}) {
    ASSERT_TRUE(certs.MakeSigned(cn, "client_ca", "DNS:client"));
  }
  StartServer({"--tls-cert", certs.Pem("server"), "--tls-key", certs.Key("server"),
               "--tls-client-ca", certs.Pem("client_ca"), "--tokens-file",
               TokensFile("alice -\nbob -\nops tok-ops admin\n")});
  const auto tls_stub = [&](const std::string& client) {
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = testing::ReadText(certs.Pem("server_ca"));
    ssl.pem_cert_chain = testing::ReadText(certs.Pem(client));
    ssl.pem_private_key = testing::ReadText(certs.Key(client));
    grpc::ChannelArguments args;
    args.SetSslTargetNameOverride("localhost");
    return v1::Radiosity::NewStub(
        grpc::CreateCustomChannel(server_->address(), grpc::SslCredentials(ssl), args));
  };
  stub_ = tls_stub("alice");
  const std::string sha = UploadCornell();
  v1::Job job;
  ASSERT_TRUE(Submit(SmallOptions(100, "jacobi"), &job, sha).ok());
  EXPECT_EQ(job.owner(), "alice");
  EXPECT_EQ(ListedIds(), std::vector<std::string>{job.job_id()});

  stub_ = tls_stub("bob");
  ExpectNotFoundAsMissing(GetJob(job.job_id()), job.job_id());
  EXPECT_TRUE(ListedIds().empty());
  As("tok-ops");  // bob's certificate, the admin's token: the token decides
  EXPECT_TRUE(GetJob(job.job_id()).ok());
  As("");

  stub_ = tls_stub("nobody");  // a good certificate whose CN is no principal
  EXPECT_EQ(GetJob(job.job_id()).error_code(), grpc::StatusCode::UNAUTHENTICATED);
}

// radfluxd with `flags`: its exit status and what it printed (stdout and stderr).
int RunRadfluxd(const std::string& flags, std::string* output) {
  FILE* pipe = popen((testing::RadfluxdPath() + " " + flags + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return -1;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof(buffer), pipe)) > 0;) output->append(buffer, n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(PrincipalsTest, ABadTokensFileLineIsRefusedWithFileAndLine) {
  const std::string base = "--listen 127.0.0.1:0 --data-dir " + data_dir_ + " --tokens-file ";
  const struct {
    const char* text;
    const char* error;
  } cases[] = {
      {"alice tok-a\n# fine\nbob tok-b frobnicate\n",
       ":3: unknown field 'frobnicate' (expected admin, running_jobs=N, patches=N or "
       "cpu_seconds=S)"},
      {"alice tok-a\nbob tok-a\n", ":2: the token of 'bob' is already the token of line 1"},
      {"alice\n", ":1: expected 'PRINCIPAL TOKEN"},
      {"alice tok-a running_jobs=-1\n", ":1: running_jobs needs a whole number >= 0"},
      {"al/ce tok-a\n", ":1: bad principal name 'al/ce'"},
      {"alice tok-a\nalice tok-b\n", ":2: principal 'alice' already defined on line 1"},
  };
  for (const auto& c : cases) {
    const std::string path = TokensFile(c.text);
    std::string output;
    EXPECT_EQ(RunRadfluxd(base + path, &output), 2) << output;
    EXPECT_NE(output.find(path + c.error), std::string::npos) << output;
  }
  std::string output;
  EXPECT_EQ(RunRadfluxd(base + TokensFile("alice tok-a\n") + " --worker-token tok-a", &output), 2);
  EXPECT_NE(output.find("--worker-token must differ"), std::string::npos) << output;
}

}  // namespace
}  // namespace radflux
