#include "client/view/view_content.h"

#include <google/protobuf/util/json_util.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "client/output_flags.h"
#include "solver/output/tone_map.h"
#include "wire/proto_convert.h"

namespace radflux::cli {
namespace {

template <typename T>
void Append(std::string* out, T value) {
  out->append(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

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

nlohmann::json ViewInfo(const std::string& job_id, const v1::SolveOptions& options,
                        size_t patches) {
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(options, &json);
  return {{"job_id", job_id},
          {"patches", patches},
          {"options", nlohmann::json::parse(json.empty() ? "{}" : json)}};
}

void PublishEvent(const v1::JobEvent& event, JobProgress& words, ViewState* state) {
  const ProgressWords w = words.Update(event, std::chrono::steady_clock::now());
  const v1::Progress& p = event.progress();
  state->Publish({{"state", v1::JobState_Name(event.state())}, {"phase", w.phase},
                  {"fraction", w.fraction}, {"eta_seconds", w.eta_seconds}, {"detail", w.detail},
                  {"iteration", p.iteration()}, {"residual", p.residual()}},
                 p.iteration(), p.residual());
}

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

// Through a scratch file: WriteOutputs writes files.
void PublishRadiosity(int iteration, const std::vector<Rgb>& b, ViewState* state) {
  const v1::Snapshot snapshot = ToProtoSnapshot(iteration, b, {}, v1::SNAPSHOT_FORMAT_FLOAT16);
  absl::StatusOr<ViewSnapshot> view = ToViewSnapshot(snapshot, b.size());
  if (view.ok()) state->PublishSnapshot(*std::move(view));  // it is float16 RGB of b.size()
}

absl::StatusOr<std::string> GlbBytes(const Scene& scene, const PatchMesh& mesh,
                                     const std::vector<Rgb>& b) {
  std::string path = (std::filesystem::temp_directory_path() / "radflux-view-XXXXXX").string();
  const int fd = ::mkstemp(path.data());
  if (fd < 0) return absl::InternalError(absl::StrCat("mkstemp: ", std::strerror(errno)));
  ::close(fd);
  const std::string glb = path + ".glb";
  OutputFlags flags;
  flags.out = glb;
  absl::Status s = WriteOutputs(flags, scene, mesh, b, {}, /*seed=*/1, 1);
  std::stringstream bytes;
  bytes << std::ifstream(glb, std::ios::binary).rdbuf();
  std::filesystem::remove(path);
  std::filesystem::remove(glb);
  if (!s.ok()) return s;
  return bytes.str();
}

}  // namespace radflux::cli
