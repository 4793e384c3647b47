// Scenes of several files through the service (issue 19): `radflux submit` sends the scene
// file with the files it names as one bundle, and radfluxd reads it with the import rules
// of the job, through the same loaders and rules as `radflux solve`. Each served B is
// compared bit for bit with the same scene solved in-process from disk (LoadScene + RunJob,
// two threads on both sides, as in ServiceTest.SubmitWatchResultEqualsInProcessRunJobBitForBit).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "absl/strings/str_replace.h"
#include "solver/scene/load_scene.h"
#include "tests/integration/service_fixture.h"
#include "tests/unit/gltf_test_builder.h"
#include "wire/scene_bundle.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

class BundleTest : public testing::ServiceFixture {
 public:
  void SetUp() override {
    ServiceFixture::SetUp();
    scene_dir_ = data_dir_ + "_scenes";
  }
  void TearDown() override {
    ServiceFixture::TearDown();
    fs::remove_all(scene_dir_);
  }

  // Writes `bytes` to scene_dir_/`path` (folders made); the full path.
  std::string Write(const std::string& path, const std::string& bytes) {
    const fs::path full = fs::path(scene_dir_) / path;
    fs::create_directories(full.parent_path());
    std::ofstream(full, std::ios::binary) << bytes;
    return full.string();
  }

  // Uploads `files` as a bundle in chunks of 1000 bytes.
  grpc::Status UploadBundle(const std::vector<BundleFile>& files, v1::SceneRef* ref) {
    StoredScene scene;
    scene.files = files;
    std::vector<v1::SceneChunk> chunks = ToSceneChunks(scene, BundleContentHash(files));
    std::string data;
    for (size_t k = 1; k < chunks.size(); ++k) data += chunks[k].data();
    auto context = Context();
    auto writer = stub_->UploadScene(context.get(), ref);
    v1::SceneChunk chunk;
    *chunk.mutable_header() = chunks[0].header();
    for (size_t at = 0; at == 0 || at < data.size(); at += 1000) {
      chunk.set_data(data.substr(at, 1000));
      if (!writer->Write(chunk)) break;
      chunk.clear_header();
    }
    writer->WritesDone();
    return writer->Finish();
  }

  // Reads the scene at `path` as `radflux submit` does and uploads it; its address.
  std::string UploadScene(const std::string& path) {
    absl::StatusOr<std::vector<BundleFile>> files = ReadSceneBundle(path);
    EXPECT_TRUE(files.ok()) << files.status();
    v1::SceneRef ref;
    const grpc::Status status = UploadBundle(*files, &ref);
    EXPECT_TRUE(status.ok()) << status.error_message();
    EXPECT_EQ(ref.sha256(), BundleContentHash(*files));
    return ref.sha256();
  }

  // Submits, watches to the end and returns B (empty when the job did not succeed).
  std::vector<double> Served(const std::string& sha, const v1::SolveOptions& options) {
    v1::Job job;
    const grpc::Status status = Submit(options, &job, sha);
    EXPECT_TRUE(status.ok()) << status.error_message();
    const std::vector<v1::JobEvent> events = Watch(job.job_id());
    EXPECT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
    std::vector<double> radiosity;
    EXPECT_TRUE(Result(job.job_id(), &radiosity).ok());
    return radiosity;
  }

  std::string scene_dir_;
};

// B of `path` solved in-process as `radflux solve` solves it: LoadScene with the job's
// import options, then RunJob on two threads.
std::vector<double> Local(const std::string& path, const v1::SolveOptions& proto) {
  absl::StatusOr<JobOptions> options = FromProto(proto);
  absl::StatusOr<ImportOptions> import = FromProto(proto.import_options());
  EXPECT_TRUE(options.ok() && import.ok());
  options->form_factors.threads = 2;
  absl::StatusOr<Scene> scene = LoadScene(path, *import);
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return {};
  absl::StatusOr<JobResult> result = RunJob(*std::move(scene), *options);
  EXPECT_TRUE(result.ok()) << result.status();
  if (!result.ok()) return {};
  std::vector<double> values;
  for (const Rgb& b : result->solve.radiosity) values.insert(values.end(), b.begin(), b.end());
  return values;
}

std::vector<std::string> Paths(const std::vector<BundleFile>& files) {
  std::vector<std::string> paths;
  for (const BundleFile& f : files) paths.push_back(f.path);
  return paths;
}

// The Cornell box with its MTL in a subfolder and the white material's Kd at 1 (clamped by
// the import rules to --max-reflectance).
std::string WriteCornell(BundleTest& t) {
  t.Write("room/mats/box.mtl",
          absl::StrReplaceAll(testing::kMtl, {{"Kd 0.75 0.75 0.75", "Kd 1 1 1"}}));
  return t.Write(
      "room/box.obj",
      absl::StrReplaceAll(testing::kObj, {{"mtllib cornell_box.mtl", "mtllib mats/box.mtl"}}));
}

TEST_F(BundleTest, ObjWithMtlInASubfolderSolvesAsLocallyAndImportFlagsActTheSame) {
  StartServer();
  const std::string obj = WriteCornell(*this);
  absl::StatusOr<std::vector<BundleFile>> files = ReadSceneBundle(obj);
  ASSERT_TRUE(files.ok()) << files.status();
  EXPECT_EQ(Paths(*files), (std::vector<std::string>{"box.obj", "mats/box.mtl"}));
  const std::string sha = UploadScene(obj);

  v1::SolveOptions options = testing::SmallOptions(300, "cg");
  const std::vector<double> by_default = Served(sha, options);
  testing::ExpectBitIdentical(by_default, Local(obj, options), "default import rules");
  options.mutable_import_options()->set_max_reflectance(0.5);
  const std::vector<double> clamped = Served(sha, options);
  testing::ExpectBitIdentical(clamped, Local(obj, options), "--max-reflectance 0.5");
  ASSERT_EQ(clamped.size(), by_default.size());
  EXPECT_NE(clamped, by_default) << "--max-reflectance changes the served B";

  // --strict refuses the Kd 1 at submit, as `radflux solve --strict` does at load.
  options.mutable_import_options()->set_strict(true);
  v1::Job job;
  const grpc::Status strict = Submit(options, &job, sha);
  EXPECT_EQ(strict.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(strict.error_message().find("reflectance Kd 1 is outside [0,1)"), std::string::npos)
      << strict.error_message();
}

// Two unit squares facing each other as glTF with its buffer in a subfolder: "lamp" at
// z = 1 facing down (no emission of its own: lit by --emit), "wall" at z = 0 facing up.
std::string WriteGltf(BundleTest& t) {
  testing::GltfBuilder b;
  const int positions = b.AddPositions({0, 0, 1, 0, 1, 1, 1, 1, 1, 1, 0, 1,  //
                                        0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  const int lamp = b.AddMaterial(
      {{"name", "lamp"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"metallicFactor", 0}}}});
  const int wall = b.AddMaterial(
      {{"name", "wall"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.6, 0.4, 1}}, {"metallicFactor", 0}}}});
  const int mesh = b.AddMesh(
      "squares",
      {testing::GltfBuilder::Primitive(positions, b.AddIndices({0, 1, 2, 0, 2, 3}), 4, lamp),
       testing::GltfBuilder::Primitive(positions, b.AddIndices({4, 5, 6, 4, 6, 7}), 4, wall)});
  b.SetScene({b.AddNode({{"mesh", mesh}, {"name", "squares"}})});
  t.Write("gltf/buffers/squares.bin", b.bin());
  return t.Write("gltf/squares.gltf", b.Gltf("buffers/squares.bin"));
}

TEST_F(BundleTest, GltfWithItsBinSolvesAsLocallyWithEmitAndIsRefusedWithoutAnEmitter) {
  StartServer();
  const std::string gltf = WriteGltf(*this);
  absl::StatusOr<std::vector<BundleFile>> files = ReadSceneBundle(gltf);
  ASSERT_TRUE(files.ok()) << files.status();
  EXPECT_EQ(Paths(*files), (std::vector<std::string>{"squares.gltf", "buffers/squares.bin"}));
  const std::string sha = UploadScene(gltf);  // no emitter yet: uploads all the same

  v1::SolveOptions options = testing::SmallOptions(50, "cg");
  options.clear_target_patches();
  options.set_max_edge(0.25);  // the same patches on each side of a two-sided face
  v1::Job job;
  const grpc::Status unlit = Submit(options, &job, sha);
  EXPECT_EQ(unlit.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(unlit.error_message().find("--emit"), std::string::npos) << unlit.error_message();

  v1::MaterialEmission* emit = options.mutable_import_options()->add_emit();
  emit->set_material("lamp");
  emit->mutable_radiance()->set_red(1);
  emit->mutable_radiance()->set_green(2);
  emit->mutable_radiance()->set_blue(3);
  const std::vector<double> served = Served(sha, options);
  testing::ExpectBitIdentical(served, Local(gltf, options), "glTF + .bin with --emit lamp=1,2,3");
  options.mutable_import_options()->set_two_sided(true);
  const std::vector<double> two_sided = Served(sha, options);
  testing::ExpectBitIdentical(two_sided, Local(gltf, options), "with --two-sided");
  EXPECT_EQ(two_sided.size(), 2 * served.size()) << "--two-sided doubles the patches";
}

TEST_F(BundleTest, MgfWithIncludesSolvesAsLocally) {
  StartServer();
  Write("mgf/mats/lamp.mgf", "m lamp =\n sides 1\n ed 100\n");
  Write("mgf/parts/lamp.mgf",
        "i ../mats/lamp.mgf\nv l0 =\n p 0 0 1\nv l1 =\n p 0 1 1\nv l2 =\n p 1 1 1\n"
        "v l3 =\n p 1 0 1\nf l0 l1 l2 l3\n");
  const std::string main =
      Write("mgf/scene.mgf",
            "m floor =\n c\n  cxy .4 .35\n rd .6\nv f0 =\n p 0 0 0\nv f1 =\n p 1 0 0\n"
            "v f2 =\n p 1 1 0\nv f3 =\n p 0 1 0\nf f0 f1 f2 f3\ni parts/lamp.mgf\n");
  absl::StatusOr<std::vector<BundleFile>> files = ReadSceneBundle(main);
  ASSERT_TRUE(files.ok()) << files.status();
  EXPECT_EQ(Paths(*files),
            (std::vector<std::string>{"scene.mgf", "parts/lamp.mgf", "mats/lamp.mgf"}));
  const std::string sha = UploadScene(main);
  v1::SolveOptions options = testing::SmallOptions(50, "cg");
  testing::ExpectBitIdentical(Served(sha, options), Local(main, options), "MGF with includes");
}

TEST_F(BundleTest, PathsThatEscapeTheBundleAreRefusedNamingThePath) {
  StartServer();
  for (const std::string bad : {"../../etc/passwd", "/etc/passwd", "a/../../b", "a//b"}) {
    v1::SceneRef ref;
    const grpc::Status s = UploadBundle({{"scene.mgf", "f a b c\n"}, {bad, "x"}}, &ref);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << bad;
    EXPECT_NE(s.error_message().find("bundle path '" + bad + "'"), std::string::npos)
        << s.error_message();
  }
  v1::SceneRef ref;
  grpc::Status s = UploadBundle({{"x.mgf", "\n"}, {"x.mgf", "\n"}}, &ref);
  EXPECT_NE(s.error_message().find("'x.mgf' is given twice"), std::string::npos)
      << s.error_message();
  // A scene naming a file outside the bundle reads it as missing, never from the server's
  // disk: the include below exists there, and is still not found.
  s = UploadBundle({{"in/scene.mgf", "i ../../../../../../../etc/hostname\n"}}, &ref);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(
      s.error_message().find("in/scene.mgf:1: cannot include '../../../../../../etc/hostname'"),
      std::string::npos)
      << s.error_message();
}

TEST(SceneBundle, AddressIgnoresTheOrderOfTheNamedFilesButNotTheirPathsOrBytes) {
  const std::vector<BundleFile> files = {{"a.obj", "o"}, {"b.mtl", "m"}, {"c.png", "p"}};
  const std::string sha = BundleContentHash(files);
  EXPECT_EQ(sha, BundleContentHash({files[0], files[2], files[1]}));
  EXPECT_NE(sha, BundleContentHash({files[1], files[0], files[2]})) << "the scene file is first";
  EXPECT_NE(sha, BundleContentHash({files[0], files[1], {"d.png", "p"}}));
  EXPECT_NE(sha, BundleContentHash({files[0], files[1], {"c.png", "q"}}));
  EXPECT_NE(sha, BundleContentHash({{"a.obj", "ob"}, {"b.mtl", ""}, files[2]}))
      << "sizes keep the split between files";
}

// What `radflux submit` sends for its import flags is what the server reads back.
TEST(ImportOptionsProto, RoundTripsEveryFieldAndUnsetMeansTheDefaults) {
  ImportOptions options;
  options.max_reflectance = 0.7;
  options.strict = true;
  options.two_sided = true;
  options.curve_segments = 24;
  options.emit = {{"lamp", {1, 2, 3}}, {"sky", {0, 0.5, 0}}};
  absl::StatusOr<ImportOptions> back = FromProto(ToProto(options));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->max_reflectance, 0.7);
  EXPECT_TRUE(back->strict && back->two_sided);
  EXPECT_EQ(back->curve_segments, 24);
  EXPECT_EQ(back->emit, options.emit);
  absl::StatusOr<ImportOptions> unset = FromProto(v1::ImportOptions{});
  ASSERT_TRUE(unset.ok());
  EXPECT_EQ(unset->max_reflectance, ImportOptions{}.max_reflectance);
  EXPECT_EQ(unset->curve_segments, ImportOptions{}.curve_segments);
  v1::ImportOptions negative = ToProto(options);
  negative.mutable_emit(1)->mutable_radiance()->set_green(-1);
  EXPECT_NE(FromProto(negative).status().message().find("--emit 'sky=0,-1,0'"), std::string::npos)
      << FromProto(negative).status();
}

}  // namespace
}  // namespace radflux
