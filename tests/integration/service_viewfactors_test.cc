// A view-factor job through the Radiosity API (issue 23): its options are checked by the
// server as `radflux viewfactors` checks its flags (INVALID_ARGUMENT naming the flag); it is
// watched like any job (rows of surfaces, then SUCCEEDED); its result is the view-factor
// file, here the unit cube's: Howell's closed forms, reciprocity and closure.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "absl/strings/str_split.h"
#include "tests/integration/service_fixture.h"

namespace radflux::testing {
namespace {

// The inside of a unit cube, each face its own object (faces inward).
constexpr const char* kCube = R"(usemtl grey
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
o floor
f 1 2 3 4
o ceiling
f 5 8 7 6
o south
f 1 5 6 2
o east
f 2 6 7 3
o north
f 3 7 8 4
o west
f 4 8 5 1
)";

// Howell's catalogue: parallel unit squares one apart (C-11), perpendicular unit squares
// with a common edge (C-14).
constexpr double kOpposite = 0.1998243;
constexpr double kAdjacent = 0.2000438;

class ViewFactorService : public ServiceFixture {
 public:
  std::string UploadCube() {
    v1::SceneRef ref;
    const grpc::Status status = Upload(kCube, "newmtl grey\nKd 0.5 0.5 0.5\n", &ref);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return ref.sha256();
  }
  // The job's view-factor file and sky-view-factor file, as GetResult streams them.
  grpc::Status Files(const std::string& job_id, std::string* factors, std::string* sky) {
    v1::GetResultRequest request;
    request.set_job_id(job_id);
    auto context = Context();
    auto reader = stub_->GetResult(context.get(), request);
    v1::ResultChunk chunk;
    while (reader->Read(&chunk)) {
      if (!chunk.has_view_factor_file()) continue;
      const v1::ViewFactorFileChunk& f = chunk.view_factor_file();
      std::string& file = f.file() == v1::VIEW_FACTOR_FILE_SKY ? *sky : *factors;
      EXPECT_EQ(f.offset(), file.size());
      file += f.data();
    }
    return reader->Finish();
  }
};

v1::SolveOptions ViewFactors(const std::string& by = "face") {
  v1::SolveOptions options;
  options.mutable_viewfactors()->set_by(by);
  return options;
}

TEST_F(ViewFactorService, BadOptionsAreRefusedNamingTheirFlag) {
  StartServer();
  const std::string sha = UploadCube();
  const auto refused = [&](const v1::SolveOptions& options, const std::string& text) {
    v1::Job job;
    const grpc::Status status = Submit(options, &job, sha);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << text;
    EXPECT_NE(status.error_message().find(text), std::string::npos) << status.error_message();
  };
  v1::SolveOptions o = ViewFactors("room");
  refused(o, "--by 'room': expected object, group or face");
  o = ViewFactors();
  o.mutable_viewfactors()->set_format("xml");
  refused(o, "--format 'xml': expected csv, sparse or view3d");
  o = ViewFactors();
  o.mutable_viewfactors()->set_min_vf(2);
  refused(o, "--min-vf 2 is outside [0, 1]");
  o = ViewFactors();
  o.mutable_viewfactors()->set_far_ratio(std::nan(""));
  refused(o, "--far-ratio nan is outside");
  o = ViewFactors();
  o.mutable_viewfactors()->set_integration("exact");
  refused(o, "--integration 'exact': expected auto, adaptive or patches");
  o = ViewFactors();
  o.set_solver("jacobi");
  refused(o, "--solver is for radflux solve only");
  o = ViewFactors();  // every surface one face: auto integrates per pair
  o.set_target_patches(100);
  refused(o, "--patches applies to --integration patches");
  o = ViewFactors();
  o.mutable_viewfactors()->set_integration("patches");
  o.mutable_viewfactors()->set_vf_tolerance(0.01);
  refused(o, "--vf-tolerance applies to adaptive integration; this run uses patch rows "
             "(--integration patches)");
}

TEST_F(ViewFactorService, CubeJobIsWatchedAndGivesHowellsFactors) {
  StartServer();
  const std::string sha = UploadCube();
  v1::Job job;
  ASSERT_TRUE(Submit(ViewFactors(), &job, sha).ok());
  const std::vector<v1::JobEvent> events =
      Watch(job.job_id(), [](const v1::JobEvent& e) { return e.state() >= v1::JOB_STATE_SUCCEEDED; });
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  bool rows_seen = false;
  for (const v1::JobEvent& e : events) {
    if (e.phase() == v1::PHASE_SOLVE) ADD_FAILURE() << "a view-factor job has no solve";
    if (e.phase() == v1::PHASE_ROWS && e.progress().rows_total() == 6) {
      rows_seen = rows_seen || e.progress().rows_done() == 6;
    }
  }
  EXPECT_TRUE(rows_seen) << "no progress event with 6 of 6 surface rows";
  std::string csv, sky;
  ASSERT_TRUE(Files(job.job_id(), &csv, &sky).ok());
  std::vector<std::string> lines = absl::StrSplit(csv, '\n', absl::SkipEmpty());
  ASSERT_EQ(lines.size(), 7u) << csv;
  EXPECT_EQ(lines[0], "from,face0,face1,face2,face3,face4,face5");
  std::vector<std::vector<double>> f;
  for (size_t i = 1; i < lines.size(); ++i) {
    std::vector<std::string> fields = absl::StrSplit(lines[i], ',');
    ASSERT_EQ(fields.size(), 7u) << lines[i];
    f.emplace_back();
    for (size_t j = 1; j < fields.size(); ++j) f.back().push_back(std::stod(fields[j]));
  }
  const int opposite[6] = {1, 0, 4, 5, 2, 3};  // floor-ceiling, south-north, east-west
  for (int i = 0; i < 6; ++i) {
    double sum = 0;
    for (int j = 0; j < 6; ++j) {
      sum += f[i][j];
      const double expected = i == j ? 0 : j == opposite[i] ? kOpposite : kAdjacent;
      EXPECT_NEAR(f[i][j], expected, 1e-3) << i << " -> " << j;
      EXPECT_EQ(f[i][j], f[j][i]) << "reciprocity (equal areas) " << i << ", " << j;
    }
    EXPECT_NEAR(sum, 1, 2e-3) << "closure of row " << i;
  }
  std::vector<std::string> sky_lines = absl::StrSplit(sky, '\n', absl::SkipEmpty());
  ASSERT_EQ(sky_lines.size(), 7u) << sky;
  EXPECT_EQ(sky_lines[0].front(), '#');
  for (size_t i = 1; i < sky_lines.size(); ++i) EXPECT_LT(std::stod(sky_lines[i]), 2e-3);
}

}  // namespace
}  // namespace radflux::testing
