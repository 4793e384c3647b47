#include "client/view/view_feed.h"

#include <google/protobuf/util/json_util.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "client/job_fetch.h"
#include "client/job_progress.h"
#include "client/job_watch.h"
#include "client/output_flags.h"
#include "solver/output/tone_map.h"
#include "wire/proto_convert.h"

namespace radflux::cli {
namespace {

template <typename T>
void Append(std::string* out, T value) {
  out->append(reinterpret_cast<const char*>(&value), sizeof value);
}

// The mesh for the page, little-endian: uint32 vertex count V, uint32 patch count P,
// float32 xyz[3V] (solver coordinates), uint32 corners[4P] (v[3] == v[2]: a triangle).
std::string MeshBytes(const PatchMesh& mesh) {
  std::string out;
  out.reserve(8 + 12 * mesh.positions.size() + 16 * mesh.size());
  Append(&out, static_cast<uint32_t>(mesh.positions.size()));
  Append(&out, static_cast<uint32_t>(mesh.size()));
  for (const Vec3& p : mesh.positions) {
    for (double c : {p.x, p.y, p.z}) Append(&out, static_cast<float>(c));
  }
  for (const Patch& patch : mesh.patches) {
    for (uint32_t v : patch.v) Append(&out, v);
  }
  return out;
}

nlohmann::json Info(const v1::Job& job, const PatchMesh& mesh) {
  std::string options;
  (void)google::protobuf::util::MessageToJsonString(job.options(), &options);
  return {{"job_id", job.job_id()},
          {"scene_sha256", job.scene_sha256()},
          {"patches", mesh.size()},
          {"options", nlohmann::json::parse(options.empty() ? "{}" : options)}};
}

// The newest B as the page gets it, with the PNG writer's auto exposure.
absl::StatusOr<ViewSnapshot> ToViewSnapshot(const v1::Snapshot& snapshot, size_t patches) {
  if (snapshot.patch_count() != patches || snapshot.bands_size() != kBands ||
      snapshot.format() != v1::SNAPSHOT_FORMAT_FLOAT16) {
    return absl::DataLossError(absl::StrCat("snapshot of ", snapshot.patch_count(),
                                            " patches for a mesh of ", patches));
  }
  absl::StatusOr<std::vector<float>> values = SnapshotValues(snapshot);
  if (!values.ok()) return values.status();
  std::vector<Rgb> radiance(patches);
  for (size_t p = 0; p < patches; ++p) {
    for (int b = 0; b < kBands; ++b) radiance[p][b] = (*values)[p * kBands + b] / M_PI;
  }
  return ViewSnapshot{snapshot.iteration(), 0, snapshot.data(), AutoExposureScale(radiance)};
}

// The GLB `radflux result JOB --out X.glb` writes, as bytes (through a scratch file).
absl::StatusOr<std::string> GlbBytes(const JobGeometry& geometry, const std::vector<Rgb>& b) {
  std::string path = (std::filesystem::temp_directory_path() / "radflux-view-XXXXXX").string();
  const int fd = ::mkstemp(path.data());
  if (fd < 0) return absl::InternalError(absl::StrCat("mkstemp: ", std::strerror(errno)));
  ::close(fd);
  const std::string glb = path + ".glb";
  OutputFlags flags;
  flags.out = glb;
  absl::Status s = WriteOutputs(flags, geometry.scene, geometry.mesh, b, 1);
  std::stringstream bytes;
  bytes << std::ifstream(glb, std::ios::binary).rdbuf();
  std::filesystem::remove(path);
  std::filesystem::remove(glb);
  if (!s.ok()) return s;
  return bytes.str();
}

// The end of a job that succeeded: its final B as the last snapshot, its report, its GLB.
absl::Status PublishResult(Client& client, const std::string& job_id, const JobGeometry& geometry,
                           int last_iteration, ViewState* state) {
  absl::StatusOr<StreamedResult> result = FetchResult(client, job_id, /*report_only=*/false);
  if (!result.ok()) return result.status();
  if (!SameMesh(geometry.mesh, *result)) {
    return absl::DataLossError("the scene re-meshed here differs from the server's mesh");
  }
  const v1::Snapshot last =
      ToProtoSnapshot(last_iteration, result->radiosity, {}, v1::SNAPSHOT_FORMAT_FLOAT16);
  absl::StatusOr<ViewSnapshot> snapshot = ToViewSnapshot(last, geometry.mesh.size());
  if (!snapshot.ok()) return snapshot.status();
  state->PublishSnapshot(*std::move(snapshot));
  absl::StatusOr<std::string> glb = GlbBytes(geometry, result->radiosity);
  if (!glb.ok()) return glb.status();
  state->End(result->report, *std::move(glb));
  return absl::OkStatus();
}

absl::Status Feed(Client& client, const std::string& job_id, int reconnect_seconds,
                  ViewState* state) {
  v1::Job job;
  if (absl::Status s = FetchJob(client, job_id, &job); !s.ok()) return s;
  absl::StatusOr<JobGeometry> geometry = FetchGeometry(client, job);
  if (!geometry.ok()) return geometry.status();
  state->SetInfo(Info(job, geometry->mesh), MeshBytes(geometry->mesh));
  absl::StatusOr<JobOptions> options = FromProto(job.options());
  JobProgress words(options.ok() ? options->solver.tolerance : 0);
  int iteration = 0;
  WatchHandlers handlers;
  handlers.event = [&](const v1::JobEvent& event) {
    const ProgressWords w = words.Update(event, std::chrono::steady_clock::now());
    iteration = std::max(iteration, event.progress().iteration());
    state->Publish({{"state", v1::JobState_Name(event.state())}, {"phase", w.phase},
                    {"fraction", w.fraction}, {"eta_seconds", w.eta_seconds},
                    {"detail", w.detail}, {"iteration", event.progress().iteration()},
                    {"residual", event.progress().residual()}},
                   event.progress().iteration(), event.progress().residual());
  };
  handlers.snapshot = [&](const v1::Snapshot& snapshot) {
    absl::StatusOr<ViewSnapshot> s = ToViewSnapshot(snapshot, geometry->mesh.size());
    if (s.ok()) state->PublishSnapshot(*std::move(s));
  };
  v1::WatchJobRequest request;
  request.set_job_id(job_id);
  request.set_snapshot_every(1);
  request.set_snapshot_format(v1::SNAPSHOT_FORMAT_FLOAT16);
  absl::StatusOr<WatchOutcome> outcome = FollowJob(client, request, handlers, reconnect_seconds);
  if (!outcome.ok()) return outcome.status();
  if (outcome->state != v1::JOB_STATE_SUCCEEDED) {
    state->End("", "");
    return absl::OkStatus();
  }
  return PublishResult(client, job_id, *geometry, iteration, state);
}

}  // namespace

void FeedJobView(Client& client, const std::string& job_id, int reconnect_seconds,
                 ViewState* state) {
  if (absl::Status s = Feed(client, job_id, reconnect_seconds, state); !s.ok()) {
    state->Fail(std::string(s.message()));
  }
}

}  // namespace radflux::cli
