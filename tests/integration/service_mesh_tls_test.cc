// Integration tests of radfluxd for structured Mesh uploads, client certificates (mutual
// TLS) and watch sequence numbers across a kill -9 restart. Each test starts its own server
// on a loopback port it picks, with a fresh data directory.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "radflux/v1/radiosity.grpc.pb.h"
#include "solver/scene/obj_loader.h"
#include "tests/integration/certificates.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/test_helpers.h"
#include "wire/scene_hash.h"
#include "wire/scene_stream.h"

namespace radflux {
namespace {

using testing::Certificates;
using testing::ExpectBitIdentical;
using testing::kMtl;
using testing::kObj;
using testing::ReadText;
using testing::SmallOptions;

class MeshUploadTest : public testing::ServiceFixture {
 public:
  // Uploads `bytes` as a serialized Mesh in chunks of 1000 bytes.
  grpc::Status UploadMesh(const std::string& bytes, v1::SceneRef* ref) {
    auto context = Context();
    auto writer = stub_->UploadScene(context.get(), ref);
    v1::SceneChunk chunk;
    chunk.mutable_header()->set_name("mesh");
    chunk.mutable_header()->set_mesh_size(bytes.size());
    for (size_t at = 0; at == 0 || at < bytes.size(); at += 1000) {
      chunk.set_data(bytes.substr(at, 1000));
      if (!writer->Write(chunk)) break;
      chunk.clear_header();
    }
    writer->WritesDone();
    return writer->Finish();
  }

  // Submits `sha` with `options`, watches it to its end and returns its B.
  std::vector<double> Solve(const std::string& sha, const v1::SolveOptions& options) {
    v1::Job job;
    EXPECT_TRUE(Submit(options, &job, sha).ok());
    const std::vector<v1::JobEvent> events = Watch(job.job_id());
    EXPECT_FALSE(events.empty());
    if (!events.empty()) {
      EXPECT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
    }
    std::vector<double> radiosity;
    EXPECT_TRUE(Result(job.job_id(), &radiosity).ok());
    return radiosity;
  }
};

void SetRgb(const Rgb& rgb, v1::Rgb* out) {
  out->set_red(rgb[0]);
  out->set_green(rgb[1]);
  out->set_blue(rgb[2]);
}

// `scene` as a Mesh: the same positions, faces, names and materials, with the emitted
// radiance L_e = E / pi (checked to give back E exactly: E = pi * L_e on the server).
v1::Mesh MeshOf(const Scene& scene) {
  v1::Mesh mesh;
  for (const Vec3& p : scene.positions) {
    mesh.add_positions(p.x);
    mesh.add_positions(p.y);
    mesh.add_positions(p.z);
  }
  for (const Face& f : scene.faces) {
    v1::MeshFace* face = mesh.add_faces();
    face->mutable_vertices()->Add(f.vertices.begin(), f.vertices.end());
    face->set_material(f.material);
    face->set_object(scene.objects[f.object]);
    face->set_group(scene.groups[f.group]);
  }
  for (const Material& m : scene.materials) {
    v1::MeshMaterial* material = mesh.add_materials();
    material->set_name(m.name);
    SetRgb(m.reflectance, material->mutable_reflectance());
    Rgb radiance{};
    for (int b = 0; b < kBands; ++b) {
      radiance[b] = m.emission[b] / std::numbers::pi;
      EXPECT_EQ(std::numbers::pi * radiance[b], m.emission[b]) << m.name << " band " << b;
    }
    SetRgb(radiance, material->mutable_emitted_radiance());
    if (m.opacity != 1) material->set_opacity(m.opacity);
  }
  return mesh;
}

TEST_F(MeshUploadTest, CornellBoxAsMeshSolvesBitIdenticalToItsObjUpload) {
  StartServer();
  const std::string obj_sha = UploadCornell();
  absl::StatusOr<Scene> scene = LoadObjText(kObj, kMtl, "cornell_box.obj");
  ASSERT_TRUE(scene.ok()) << scene.status();
  const std::string bytes = MeshOf(*scene).SerializeAsString();

  v1::SceneRef ref;
  grpc::Status status = UploadMesh(bytes, &ref);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(ref.sha256(), MeshContentHash(bytes));
  EXPECT_NE(ref.sha256(), obj_sha);
  EXPECT_EQ(ref.faces(), scene->faces.size());
  EXPECT_EQ(ref.materials(), scene->materials.size());
  EXPECT_FALSE(ref.already_stored());
  v1::SceneRef again;
  ASSERT_TRUE(UploadMesh(bytes, &again).ok());
  EXPECT_EQ(again.sha256(), ref.sha256());
  EXPECT_TRUE(again.already_stored()) << "the same mesh is stored once";

  // GetScene gives the mesh back as uploaded (what `radflux result` re-meshes from).
  v1::GetSceneRequest get;
  get.set_sha256(ref.sha256());
  auto context = Context();
  auto reader = stub_->GetScene(context.get(), get);
  absl::StatusOr<StoredScene> stored = ReadSceneChunks(*reader, ref.sha256());
  ASSERT_TRUE(stored.ok()) << stored.status();
  EXPECT_EQ(stored->mesh, bytes);
  EXPECT_TRUE(stored->obj.empty() && stored->mtl.empty());

  const v1::SolveOptions options = SmallOptions(300, "cg");
  ExpectBitIdentical(Solve(ref.sha256(), options), Solve(obj_sha, options),
                     "the Mesh upload solves to the OBJ upload's B");
}

TEST_F(MeshUploadTest, AHalfOpaquePlateKeepsItsOpacityAndSolvesBitIdenticalToLocal) {
  // The Cornell box with a grey 250 x 250 mm plate at mid height under the light, half
  // opaque: uploaded as a Mesh with the plate's opacity, it solves to the B of the same
  // scene solved in-process, bit for bit; without the field it solves as an opaque plate.
  StartServer();
  absl::StatusOr<Scene> scene = LoadObjText(
      kObj + "o plate\nusemtl plate\nv 400 300 150\nv 400 300 400\nv 150 300 400\n"
             "v 150 300 150\nf 67 68 69 70\n",
      kMtl + "newmtl plate\nKd 0.5 0.5 0.5\n", "cornell_plate.obj");
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->materials.back().name, "plate");
  scene->materials.back().opacity = 0.5;
  const v1::Mesh half = MeshOf(*scene);
  ASSERT_TRUE(half.materials().rbegin()->has_opacity());
  v1::Mesh opaque = half;
  opaque.mutable_materials()->rbegin()->clear_opacity();
  v1::SceneRef half_ref, opaque_ref;
  ASSERT_TRUE(UploadMesh(half.SerializeAsString(), &half_ref).ok());
  ASSERT_TRUE(UploadMesh(opaque.SerializeAsString(), &opaque_ref).ok());
  EXPECT_NE(half_ref.sha256(), opaque_ref.sha256());
  const v1::SolveOptions options = SmallOptions(300, "cg");
  const std::vector<double> served = Solve(half_ref.sha256(), options);
  ExpectBitIdentical(served, testing::InProcess(options, *scene),
                     "the served B of the half-opaque plate is the local B");
  EXPECT_NE(served, Solve(opaque_ref.sha256(), options)) << "the opacity reached the solver";
}

// Two unit squares facing each other, a lamp (face 0) and a wall (face 1).
v1::Mesh TwoSquares() {
  v1::Mesh mesh;
  for (double v : {0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.,
                   0., 0., 1., 1., 0., 1., 1., 1., 1., 0., 1., 1.}) {
    mesh.add_positions(v);
  }
  for (std::vector<uint32_t> vertices : {std::vector<uint32_t>{0, 1, 2, 3}, {4, 7, 6, 5}}) {
    v1::MeshFace* face = mesh.add_faces();
    face->mutable_vertices()->Add(vertices.begin(), vertices.end());
    face->set_material(mesh.faces_size() - 1);
    face->set_object(mesh.faces_size() == 1 ? "lamp" : "wall");
  }
  v1::MeshMaterial* lamp = mesh.add_materials();
  lamp->set_name("lamp");
  SetRgb({0.5, 0.5, 0.5}, lamp->mutable_reflectance());
  SetRgb({1, 1, 1}, lamp->mutable_emitted_radiance());
  v1::MeshMaterial* wall = mesh.add_materials();
  wall->set_name("wall");
  SetRgb({0.8, 0.8, 0.8}, wall->mutable_reflectance());
  return mesh;
}

TEST_F(MeshUploadTest, MalformedMeshesGetInvalidArgumentNamingTheFaceAndTheServerKeepsServing) {
  StartServer();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    std::string what;
    std::function<void(v1::Mesh&)> spoil;
    std::string message;  // a part of the expected message
  };
  const std::vector<Case> cases = {
      {"two vertices", [](v1::Mesh& m) { m.mutable_faces(1)->mutable_vertices()->Truncate(2); },
       "mesh: face 1: has 2 vertices; a face needs at least 3"},
      {"vertex index", [](v1::Mesh& m) { m.mutable_faces(0)->set_vertices(2, 99); },
       "mesh: face 0: vertex index 99 is out of range (the mesh has 8 vertices)"},
      {"material index", [](v1::Mesh& m) { m.mutable_faces(1)->set_material(5); },
       "mesh: face 1: unknown material index 5 (the mesh has 2 materials)"},
      {"NaN coordinate", [nan](v1::Mesh& m) { m.set_positions(3 * 6 + 1, nan); },
       "mesh: face 1: vertex 6 has a NaN or infinite coordinate"},
      {"infinite reflectance",
       [](v1::Mesh& m) {
         m.mutable_materials(1)->mutable_reflectance()->set_green(
             std::numeric_limits<double>::infinity());
       },
       "mesh: material 1 'wall': reflectance is NaN or infinite"},
      {"NaN radiance",
       [nan](v1::Mesh& m) { m.mutable_materials(0)->mutable_emitted_radiance()->set_blue(nan); },
       "mesh: material 0 'lamp': emitted radiance is NaN or infinite"},
      {"opacity", [](v1::Mesh& m) { m.mutable_materials(1)->set_opacity(0); },
       "mesh: material 1 'wall': opacity 0 is outside (0, 1]"},
      {"positions", [](v1::Mesh& m) { m.add_positions(1); },
       "mesh: 25 position values are not x y z triples"},
  };
  for (const Case& c : cases) {
    v1::Mesh mesh = TwoSquares();
    c.spoil(mesh);
    v1::SceneRef ref;
    const grpc::Status s = UploadMesh(mesh.SerializeAsString(), &ref);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.what;
    EXPECT_NE(s.error_message().find(c.message), std::string::npos)
        << c.what << ": " << s.error_message();
  }
  // What the import rules fix uploads, and is refused by a job with --strict (ValidateScene's
  // message, as for OBJ uploads, naming the face index).
  const std::vector<Case> strict_cases = {
      {"non-planar", [](v1::Mesh& m) { m.set_positions(3 * 6 + 2, 0); },
       "mesh (face 1 of object 'wall'): non-planar face"},
      {"reflectance range",
       [](v1::Mesh& m) { m.mutable_materials(1)->mutable_reflectance()->set_red(1.5); },
       "material 'wall': reflectance Kd 1.5 is outside [0,1)"},
  };
  for (const Case& c : strict_cases) {
    v1::Mesh mesh = TwoSquares();
    c.spoil(mesh);
    v1::SceneRef fixed;
    ASSERT_TRUE(UploadMesh(mesh.SerializeAsString(), &fixed).ok()) << c.what;
    v1::SolveOptions options = SmallOptions(8, "cg");
    options.mutable_import_options()->set_strict(true);
    v1::Job job;
    const grpc::Status s = Submit(options, &job, fixed.sha256());
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.what;
    EXPECT_NE(s.error_message().find(c.message), std::string::npos)
        << c.what << ": " << s.error_message();
  }
  v1::SceneRef ref;
  grpc::Status s = UploadMesh("\xff\xff\xff", &ref);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(s.error_message().find("not a serialized radflux.v1.Mesh"), std::string::npos)
      << s.error_message();
  {  // A header declaring both forms.
    auto context = Context();
    auto writer = stub_->UploadScene(context.get(), &ref);
    v1::SceneChunk chunk;
    chunk.mutable_header()->set_obj_size(10);
    chunk.mutable_header()->set_mesh_size(10);
    writer->Write(chunk);
    writer->WritesDone();
    s = writer->Finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(s.error_message().find("not both"), std::string::npos) << s.error_message();
  }
  // The server keeps serving: the good mesh uploads and solves.
  const std::string good = TwoSquares().SerializeAsString();
  s = UploadMesh(good, &ref);
  ASSERT_TRUE(s.ok()) << s.error_message();
  EXPECT_EQ(ref.faces(), 2u);
  const std::vector<double> b = Solve(ref.sha256(), SmallOptions(8, "cg"));
  EXPECT_FALSE(b.empty());
}

class MutualTlsTest : public testing::ServiceFixture {
 public:
  // A stub over TLS trusting `server_ca`, presenting client certificate `client` (none when
  // empty).
  std::unique_ptr<v1::Radiosity::Stub> TlsStub(const Certificates& certs,
                                               const std::string& server_ca,
                                               const std::string& client) {
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = ReadText(certs.Pem(server_ca));
    if (!client.empty()) {
      ssl.pem_cert_chain = ReadText(certs.Pem(client));
      ssl.pem_private_key = ReadText(certs.Key(client));
    }
    grpc::ChannelArguments args;
    args.SetSslTargetNameOverride("localhost");
    return v1::Radiosity::NewStub(
        grpc::CreateCustomChannel(server_->address(), grpc::SslCredentials(ssl), args));
  }
  grpc::Status List(v1::Radiosity::Stub& stub) {
    v1::ListJobsResponse list;
    grpc::ClientContext context;
    return stub.ListJobs(&context, {}, &list);
  }
};

TEST_F(MutualTlsTest, ClientCertificateOfTheClientCaIsRequired) {
  Certificates certs(data_dir_);
  ASSERT_TRUE(certs.MakeCa("server_ca"));
  ASSERT_TRUE(certs.MakeSigned("server", "server_ca", "DNS:localhost,IP:127.0.0.1"));
  ASSERT_TRUE(certs.MakeCa("client_ca"));
  ASSERT_TRUE(certs.MakeSigned("client", "client_ca", "DNS:client"));
  ASSERT_TRUE(certs.MakeCa("other_ca"));
  ASSERT_TRUE(certs.MakeSigned("stranger", "other_ca", "DNS:client"));
  StartServer({"--tls-cert", certs.Pem("server"), "--tls-key", certs.Key("server"),
               "--tls-client-ca", certs.Pem("client_ca")});

  // Without a client certificate, and with one from another CA: the handshake fails.
  std::unique_ptr<v1::Radiosity::Stub> anonymous = TlsStub(certs, "server_ca", "");
  EXPECT_EQ(List(*anonymous).error_code(), grpc::StatusCode::UNAVAILABLE);
  std::unique_ptr<v1::Radiosity::Stub> stranger = TlsStub(certs, "server_ca", "stranger");
  EXPECT_EQ(List(*stranger).error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(List(*stub_).error_code(), grpc::StatusCode::UNAVAILABLE) << "plaintext";

  // With a certificate of the client CA: the whole round trip, after the refusals.
  stub_ = TlsStub(certs, "server_ca", "client");
  ASSERT_TRUE(List(*stub_).ok());
  const std::string sha = UploadCornell();
  ASSERT_FALSE(sha.empty());
  v1::Job job;
  ASSERT_TRUE(Submit(SmallOptions(100, "cg"), &job, sha).ok());
  const std::vector<v1::JobEvent> events = Watch(job.job_id());
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().state(), v1::JOB_STATE_SUCCEEDED) << events.back().message();
  std::vector<double> radiosity;
  EXPECT_TRUE(Result(job.job_id(), &radiosity).ok());
  EXPECT_FALSE(radiosity.empty());
  EXPECT_EQ(List(*TlsStub(certs, "server_ca", "stranger")).error_code(),
            grpc::StatusCode::UNAVAILABLE);

  // The radflux client's --tls-ca/--tls-cert/--tls-key (exit 0), and without the
  // certificate (exit 1).
  const std::string cli = std::string(RADFLUX_SERVICE_CLI_PATH) + " list --server " +
                          server_->address() + " --tls-ca " + certs.Pem("server_ca");
  EXPECT_EQ(std::system((cli + " --tls-cert " + certs.Pem("client") + " --tls-key " +
                         certs.Key("client") + " >/dev/null")
                            .c_str()),
            0);
  EXPECT_NE(std::system((cli + " >/dev/null 2>&1").c_str()), 0);
}

class WatchAcrossRestartTest : public testing::ServiceFixture {
 public:
  // Watches `job_id` from after `after` with a snapshot every solver iteration, until
  // `stop(event)` or the stream's end.
  std::vector<v1::JobEvent> WatchFrom(const std::string& job_id, uint64_t after,
                                      const std::function<bool(const v1::JobEvent&)>& stop = {}) {
    v1::WatchJobRequest request;
    request.set_job_id(job_id);
    request.set_after_sequence(after);
    request.set_snapshot_every(1);
    return Watch(request, stop);
  }
};

// Checks the events a watcher got after `after`: every event is numbered above `after`, the
// events one by one without a gap or a repeat, each snapshot with the number of the event it
// follows. Returns the last number.
uint64_t ExpectResumedAfter(const std::vector<v1::JobEvent>& events, uint64_t after) {
  uint64_t last = 0;
  for (const v1::JobEvent& e : events) {
    EXPECT_GT(e.sequence(), after) << "a number the watcher saw before";
    if (e.has_snapshot()) {
      EXPECT_EQ(e.sequence(), last) << "a snapshot carries the number it follows";
    } else {
      if (last > 0) {
        EXPECT_EQ(e.sequence(), last + 1) << "events come one by one";
      }
      last = e.sequence();
    }
  }
  return last;
}

TEST_F(WatchAcrossRestartTest, ReconnectAfterKillNineGetsOnlyNewNumbersAndTheFinalState) {
  // 200 ms an iteration: southwell counts sweep-equivalents now (a few for this job), so the
  // kill must still land mid-solve after the watcher has seen iteration 3.
  StartServer({"--checkpoint-seconds", "0", "--solve-delay-ms", "200"});
  const std::string sha = UploadCornell();
  v1::SolveOptions options = SmallOptions(600, "southwell");
  options.set_tolerance(1e-5);
  v1::Job job;
  ASSERT_TRUE(Submit(options, &job, sha).ok());
  const std::vector<v1::JobEvent> before = WatchFrom(job.job_id(), 0, [](const v1::JobEvent& e) {
    return e.phase() == v1::PHASE_SOLVE && e.progress().iteration() >= 3;
  });
  ASSERT_FALSE(before.empty());
  ASSERT_EQ(before.back().state(), v1::JOB_STATE_RUNNING);
  const uint64_t seen = ExpectResumedAfter(before, 0);
  ASSERT_GT(seen, 3u);
  server_->Kill();

  StartServer();
  const std::vector<v1::JobEvent> after = WatchFrom(job.job_id(), seen);
  ASSERT_FALSE(after.empty()) << "the job's current state, not an empty stream";
  EXPECT_EQ(after.front().state(), v1::JOB_STATE_RUNNING) << "first: the stored state";
  EXPECT_EQ(after.front().phase(), v1::PHASE_SOLVE) << "and phase";
  EXPECT_EQ(after.back().state(), v1::JOB_STATE_SUCCEEDED) << after.back().message();
  const uint64_t last = ExpectResumedAfter(after, seen);
  bool snapshot = false;
  for (const v1::JobEvent& e : after) snapshot = snapshot || e.has_snapshot();
  EXPECT_TRUE(snapshot) << "snapshots asked for keep coming after the restart";

  // Reconnecting with the last number gets nothing more (no snapshot after the final event
  // either); after another restart, the final state again, numbered higher still.
  EXPECT_TRUE(WatchFrom(job.job_id(), last).empty());
  server_->Kill();
  StartServer();
  const std::vector<v1::JobEvent> final_state = WatchFrom(job.job_id(), last);
  ASSERT_EQ(final_state.size(), 1u);
  EXPECT_EQ(final_state[0].state(), v1::JOB_STATE_SUCCEEDED);
  EXPECT_GT(final_state[0].sequence(), last);
}

}  // namespace
}  // namespace radflux
