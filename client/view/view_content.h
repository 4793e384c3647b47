// What the page of `radflux view` is sent, made from a job's parts: the mesh, the info,
// progress in words, snapshots (float16 B with the PNG writer's auto exposure) and the lit
// mesh. Shared by a job followed over gRPC (view_feed) and a local solve (solve_view).
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "client/job_fetch.h"
#include "client/job_progress.h"
#include "client/view/view_state.h"
#include "radflux/v1/job.pb.h"

namespace radflux::cli {

// The mesh for the page, little-endian: uint32 vertex count V, uint32 patch count P,
// float32 xyz[3V] (solver coordinates), uint32 corners[4P] (v[3] == v[2]: a triangle).
std::string MeshBytes(const PatchMesh& mesh);

// The page's "info": job id, options (as the API's JSON), patch count.
nlohmann::json ViewInfo(const std::string& job_id, const v1::SolveOptions& options,
                        size_t patches);

// Publishes one progress event, in the words of `words`, to `state`.
void PublishEvent(const v1::JobEvent& event, JobProgress& words, ViewState* state);

// A float16 snapshot as the page gets it, with AutoExposureScale of its radiance B/pi.
// DATA_LOSS when it is not float16 RGB of `patches` patches.
absl::StatusOr<ViewSnapshot> ToViewSnapshot(const v1::Snapshot& snapshot, size_t patches);

// Publishes B (W/m^2 per patch and band) at `iteration` to `state` as a float16 snapshot.
void PublishRadiosity(int iteration, const std::vector<Rgb>& b, ViewState* state);

// The GLB `radflux result JOB --out X.glb` writes for `mesh` of `scene` lit by `b`, as bytes.
absl::StatusOr<std::string> GlbBytes(const Scene& scene, const PatchMesh& mesh,
                                     const std::vector<Rgb>& b);

}  // namespace radflux::cli
