#include "client/view/view_feed.h"

#include <algorithm>

#include "client/job_fetch.h"
#include "client/job_progress.h"
#include "client/job_watch.h"
#include "client/view/view_content.h"
#include "wire/proto_convert.h"

namespace radflux::cli {
namespace {

// The end of a job that succeeded: its final B as the last snapshot, its report, its GLB.
absl::Status PublishResult(Client& client, const std::string& job_id, const JobGeometry& geometry,
                           int last_iteration, ViewState* state) {
  absl::StatusOr<StreamedResult> result = FetchResult(client, job_id, /*report_only=*/false);
  if (!result.ok()) return result.status();
  if (!SameMesh(geometry.mesh, *result)) {
    return absl::DataLossError("the scene re-meshed here differs from the server's mesh");
  }
  PublishRadiosity(last_iteration, result->radiosity, state);
  absl::StatusOr<std::string> glb = GlbBytes(geometry.scene, geometry.mesh, result->radiosity);
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
  state->SetInfo(ViewInfo(job.job_id(), job.options(), geometry->mesh.size()),
                 MeshBytes(geometry->mesh));
  absl::StatusOr<JobOptions> options = FromProto(job.options());
  JobProgress words(options.ok() ? options->solver.tolerance : 0);
  int iteration = 0;
  WatchHandlers handlers;
  handlers.event = [&](const v1::JobEvent& event) {
    iteration = std::max(iteration, event.progress().iteration());
    PublishEvent(event, words, state);
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
