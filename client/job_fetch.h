// Fetching a job's parts from radfluxd: the job, its geometry (scene re-meshed here, as
// the server meshed it) and its streamed result. Shared by `radflux result`, `watch` and
// `view`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "client/service_client.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux::cli {

// A job's scene fetched from the server (GetScene), re-loaded and re-meshed with the job's
// options: with B, all that WriteOutputs needs. Meshing is deterministic, so this is the
// mesh the server solved on (GetResult checks it against the mesh it streams).
struct JobGeometry {
  Scene scene;
  PatchMesh mesh;
  uint64_t seed = 1;  // the job's seed, which seeds its sampled pictures as `solve`'s
};

// The job `job_id` (GetJob).
absl::Status FetchJob(Client& client, const std::string& job_id, v1::Job* job);

// The scene of `job` re-loaded and re-meshed with its options.
absl::StatusOr<JobGeometry> FetchGeometry(Client& client, const v1::Job& job);

// A finished job's result as streamed: the mesh the server solved on, B, the report.
struct StreamedResult {
  v1::Job job;
  std::vector<Vec3> positions;
  std::vector<uint32_t> vertices, faces;
  std::vector<Rgb> radiosity;  // W/m^2 per band, per patch
  std::vector<Rgb> indirect;   // B's part not straight from an emitter (empty when not sent)
  std::string report;
  uint64_t patch_count = 0;  // from the header (also when the mesh and B were not asked for)
  // A view-factor job's files (empty when report_only): what `radflux viewfactors` writes
  // to -o and to --svf.
  std::string view_factors, sky_view_factors;
};

// A finished job's result (GetResult). With `report_only`, asks for the header and the
// report alone (a server older than that request field sends everything, which is read as
// usual). DATA_LOSS when the stream does not match its header's counts.
absl::StatusOr<StreamedResult> FetchResult(Client& client, const std::string& job_id,
                                           bool report_only);

// True when `mesh` is exactly the mesh the server streamed.
bool SameMesh(const PatchMesh& mesh, const StreamedResult& r);

}  // namespace radflux::cli
