// The gRPC side of `radflux view`: follows one job on radfluxd (GetJob, GetScene, WatchJob,
// GetResult) and keeps its ViewState up to date. Token and TLS stay here, in the CLI
// process; the page only ever talks to this process.
#pragma once

#include <string>

#include "client/service_client.h"
#include "client/view/view_state.h"

namespace radflux::cli {

// Fills `state` for job `job_id` until the job ends: the info and the mesh (the scene
// re-meshed here as `radflux result` does), then each progress event and the newest
// snapshot (float16), then the report, the final B as the last snapshot and the lit mesh
// as a GLB (what `radflux result JOB --out X.glb` writes). A dropped stream is resumed for
// up to `reconnect_seconds`. A failure ends the view with ViewState::Fail.
void FeedJobView(Client& client, const std::string& job_id, int reconnect_seconds,
                 ViewState* state);

}  // namespace radflux::cli
