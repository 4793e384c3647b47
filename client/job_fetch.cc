#include "client/job_fetch.h"

#include "absl/strings/str_cat.h"
#include "solver/grouped_mesh.h"
#include "solver/scene/validation.h"
#include "wire/proto_convert.h"
#include "wire/scene_stream.h"
#include "wire/stored_scene.h"

namespace radflux::cli {

absl::Status FetchJob(Client& client, const std::string& job_id, v1::Job* job) {
  v1::GetJobRequest request;
  request.set_job_id(job_id);
  return FromGrpcStatus(client.stub().GetJob(client.Context().get(), request, job));
}

absl::StatusOr<JobGeometry> FetchGeometry(Client& client, const v1::Job& job) {
  v1::GetSceneRequest request;
  request.set_sha256(job.scene_sha256());
  auto context = client.Context();
  auto reader = client.stub().GetScene(context.get(), request);
  absl::StatusOr<StoredScene> stored = ReadSceneChunks(*reader, job.scene_sha256());
  if (!stored.ok()) return stored.status();
  absl::StatusOr<JobOptions> options = FromProto(job.options());
  if (!options.ok()) return options.status();
  absl::StatusOr<ImportOptions> import = FromProto(job.options().import_options());
  if (!import.ok()) return import.status();
  JobGeometry geometry;
  absl::StatusOr<Scene> scene = LoadStoredScene(*std::move(stored), *import);
  if (!scene.ok()) return scene.status();
  geometry.scene = *std::move(scene);
  if (absl::Status s = ValidateScene(geometry.scene); !s.ok()) return s;
  // The patches the server solved on (split and grouped as it did); the result has a B each.
  absl::StatusOr<GroupedMesh> mesh = SubdivideAndGroup(geometry.scene, JobMeshOptions(*options));
  if (!mesh.ok()) return mesh.status();
  geometry.mesh = std::move(mesh->mesh);
  geometry.seed = options->form_factors.seed;
  return geometry;
}

absl::StatusOr<StreamedResult> FetchResult(Client& client, const std::string& job_id,
                                           bool report_only) {
  v1::GetResultRequest request;
  request.set_job_id(job_id);
  request.set_report_only(report_only);
  auto context = client.Context();
  auto reader = client.stub().GetResult(context.get(), request);
  v1::ResultChunk chunk;
  StreamedResult r;
  uint64_t vertex_count = 0, patch_count = 0, factor_bytes = 0, sky_bytes = 0;
  std::vector<double> xyz, b, indirect;
  while (reader->Read(&chunk)) {
    if (chunk.has_header()) {
      r.job = chunk.header().job();
      vertex_count = chunk.header().vertex_count();
      patch_count = chunk.header().patch_count();
      factor_bytes = chunk.header().view_factor_bytes();
      sky_bytes = chunk.header().sky_view_factor_bytes();
    }
    if (chunk.has_view_factor_file()) {
      const v1::ViewFactorFileChunk& f = chunk.view_factor_file();
      std::string& file =
          f.file() == v1::VIEW_FACTOR_FILE_SKY ? r.sky_view_factors : r.view_factors;
      if (f.offset() != file.size()) {
        return absl::DataLossError("view-factor file chunks out of order in the result stream");
      }
      file += f.data();
    }
    if (chunk.has_vertices())
      xyz.insert(xyz.end(), chunk.vertices().xyz().begin(), chunk.vertices().xyz().end());
    if (chunk.has_patches()) {
      const v1::PatchChunk& p = chunk.patches();
      r.vertices.insert(r.vertices.end(), p.vertices().begin(), p.vertices().end());
      r.faces.insert(r.faces.end(), p.source_face().begin(), p.source_face().end());
      b.insert(b.end(), p.radiosity().begin(), p.radiosity().end());
      indirect.insert(indirect.end(), p.indirect().begin(), p.indirect().end());
    }
    if (chunk.part_case() == v1::ResultChunk::kReportJson) r.report = chunk.report_json();
  }
  if (absl::Status s = FromGrpcStatus(reader->Finish()); !s.ok()) return s;
  r.patch_count = patch_count;
  if (report_only && xyz.empty() && r.faces.empty() && r.view_factors.empty()) return r;
  if (r.view_factors.size() != factor_bytes || r.sky_view_factors.size() != sky_bytes) {
    return absl::DataLossError("result stream's view-factor files do not match its header's sizes");
  }
  if (xyz.size() != 3 * vertex_count || r.faces.size() != patch_count ||
      r.vertices.size() != 4 * patch_count || b.size() != kBands * patch_count) {
    return absl::DataLossError("result stream does not match its header's counts");
  }
  for (size_t i = 0; i < vertex_count; ++i)
    r.positions.push_back({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
  if (!indirect.empty() && indirect.size() != kBands * patch_count) {
    return absl::DataLossError("result stream's indirect values do not match its patches");
  }
  r.radiosity.resize(patch_count);
  for (size_t p = 0; p < patch_count; ++p)
    for (int k = 0; k < kBands; ++k) r.radiosity[p][k] = b[kBands * p + k];
  r.indirect.resize(indirect.empty() ? 0 : patch_count);
  for (size_t p = 0; p < r.indirect.size(); ++p)
    for (int k = 0; k < kBands; ++k) r.indirect[p][k] = indirect[kBands * p + k];
  return r;
}

bool SameMesh(const PatchMesh& mesh, const StreamedResult& r) {
  if (mesh.positions.size() != r.positions.size() || mesh.size() != r.faces.size()) return false;
  for (size_t i = 0; i < r.positions.size(); ++i) {
    const Vec3& a = mesh.positions[i];
    const Vec3& b = r.positions[i];
    if (a.x != b.x || a.y != b.y || a.z != b.z) return false;
  }
  for (size_t p = 0; p < mesh.size(); ++p) {
    if (mesh.patches[p].face != r.faces[p]) return false;
    for (int k = 0; k < 4; ++k)
      if (mesh.patches[p].v[k] != r.vertices[4 * p + k]) return false;
  }
  return true;
}

}  // namespace radflux::cli
