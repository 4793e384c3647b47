#include "client/job_watch.h"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "absl/strings/str_cat.h"
#include "client/exit_status.h"
#include "client/job_progress.h"
#include "client/progress_display.h"
#include "wire/proto_convert.h"

namespace radflux::cli {
namespace {

namespace fs = std::filesystem;

// Writes snapshot B of `snapshot` as DIR/snapshot_<iteration>.png with the camera flags.
absl::Status WriteSnapshotPng(const v1::Snapshot& snapshot, const JobGeometry& geometry,
                              const std::string& dir, const OutputArgs& args) {
  absl::StatusOr<std::vector<float>> values = SnapshotValues(snapshot);
  if (!values.ok()) return values.status();
  if (snapshot.patch_count() != geometry.mesh.size() || snapshot.bands_size() != kBands) {
    return absl::DataLossError(absl::StrCat("snapshot of ", snapshot.patch_count(), " patches and ",
                                            snapshot.bands_size(), " bands for a mesh of ",
                                            geometry.mesh.size()));
  }
  std::vector<Rgb> radiosity(geometry.mesh.size());
  for (size_t p = 0; p < radiosity.size(); ++p)
    for (int b = 0; b < kBands; ++b) radiosity[p][b] = (*values)[p * kBands + b];
  OutputFlags flags = args.output;
  flags.out.clear();
  flags.patch_values.clear();
  char name[64];
  std::snprintf(name, sizeof(name), "snapshot_%06d.png", snapshot.iteration());
  flags.render = (fs::path(dir) / name).string();
  // Without the indirect part (known once solved) a snapshot is Gouraud-shaded.
  return WriteOutputs(flags, geometry.scene, geometry.mesh, radiosity, {}, geometry.seed,
                      args.threads);
}

// True when a watch stream that failed with `code` before its job's final event may be
// reopened: the server went away (restart, network) rather than refused the watch.
bool StreamMayResume(grpc::StatusCode code) {
  return code == grpc::StatusCode::UNAVAILABLE || code == grpc::StatusCode::CANCELLED ||
         code == grpc::StatusCode::UNKNOWN || code == grpc::StatusCode::INTERNAL ||
         code == grpc::StatusCode::DEADLINE_EXCEEDED;
}

// One WatchJob stream from after progress->last_sequence until the job's final event (the
// stream is then cancelled: the result can be asked for at once, without waiting for the
// stream's end) or until the stream ends; returns its status.
grpc::Status WatchStream(Client& client, v1::WatchJobRequest request,
                         const WatchHandlers& handlers, WatchOutcome* progress) {
  request.set_after_sequence(progress->last_sequence);
  auto context = client.Context();
  auto reader = client.stub().WatchJob(context.get(), request);
  v1::JobEvent event;
  while (reader->Read(&event)) {
    if (event.has_snapshot()) {
      ++progress->snapshots;
      if (handlers.snapshot) handlers.snapshot(event.snapshot());
      continue;
    }
    progress->last_sequence = event.sequence();
    progress->state = event.state();
    progress->message = event.message();
    progress->verdict = SucceededJobExitCode(event);
    if (handlers.event) handlers.event(event);
    if (IsTerminal(event.state())) {
      context->TryCancel();
      break;
    }
  }
  return reader->Finish();
}

}  // namespace

absl::StatusOr<WatchOutcome> FollowJob(Client& client, const v1::WatchJobRequest& request,
                                       const WatchHandlers& handlers, int reconnect_seconds) {
  WatchOutcome progress;
  for (;;) {
    const grpc::Status status = WatchStream(client, request, handlers, &progress);
    if (IsTerminal(progress.state)) return progress;
    if (progress.last_sequence == 0 || reconnect_seconds <= 0 ||
        !StreamMayResume(status.error_code())) {
      if (!status.ok()) return FromGrpcStatus(status);
      return progress;
    }
    if (handlers.note) {
      handlers.note(absl::StrCat("radflux: watch of ", request.job_id(), " dropped after event ",
                                 progress.last_sequence, " (", status.error_message(),
                                 "); reconnecting"));
    }
    if (!client.WaitForConnected(std::chrono::system_clock::now() +
                                 std::chrono::seconds(reconnect_seconds))) {
      return absl::UnavailableError(absl::StrCat("no answer for ", reconnect_seconds, " s"));
    }
  }
}

int WatchJob(Client& client, const std::string& job_id, const std::string& snapshots_dir,
             const JobGeometry* geometry, const OutputArgs& args, int snapshot_every,
             int reconnect_seconds) {
  v1::WatchJobRequest request;
  request.set_job_id(job_id);
  request.set_snapshot_every(snapshot_every);
  // Snapshots become 8-bit PNGs here: float16 B (11 significant bits) renders the same
  // picture at half the bytes of float32.
  request.set_snapshot_format(v1::SNAPSHOT_FORMAT_FLOAT16);
  if (!snapshots_dir.empty()) {
    request.set_snapshot_every(std::max(1, snapshot_every));
    std::error_code error;
    fs::create_directories(snapshots_dir, error);
  }
  v1::Job job;
  if (absl::Status s = FetchJob(client, job_id, &job); !s.ok()) return Fail(s, client.flags());
  absl::StatusOr<JobOptions> options = FromProto(job.options());
  JobProgress words(options.ok() ? options->solver.tolerance : 0);
  ProgressDisplay display(/*quiet=*/false);
  WatchHandlers handlers;
  handlers.event = [&](const v1::JobEvent& event) {
    const ProgressWords w = words.Update(event, std::chrono::steady_clock::now());
    // A person's terminal gets the phase; a log gets the event number too (events resume
    // after it when the stream drops).
    const std::string label = display.terminal() ? w.phase
                                                 : absl::StrCat("[", event.sequence(), "] ", w.phase);
    display.Show(label, w.fraction, w.detail,
                 event.state() != v1::JOB_STATE_RUNNING || event.phase() != v1::PHASE_ROWS);
    if (IsTerminal(event.state())) display.Finish();
  };
  if (!snapshots_dir.empty()) {
    handlers.snapshot = [&](const v1::Snapshot& snapshot) {
      if (absl::Status s = WriteSnapshotPng(snapshot, *geometry, snapshots_dir, args); !s.ok()) {
        display.Line(absl::StrCat("radflux: snapshot ", snapshot.iteration(), ": ", s.message()));
      }
    };
  }
  handlers.note = [&](const std::string& line) { display.Line(line); };
  absl::StatusOr<WatchOutcome> outcome =
      FollowJob(client, request, handlers, reconnect_seconds);
  display.Finish();
  if (!outcome.ok()) return Fail(outcome.status(), client.flags());
  if (request.snapshot_every() > 0) std::cerr << outcome->snapshots << " snapshots received\n";
  if (outcome->state != v1::JOB_STATE_SUCCEEDED) {
    std::cerr << "radflux: job " << job_id << " ended " << v1::JobState_Name(outcome->state)
              << (outcome->message.empty() ? "" : ": " + outcome->message) << "\n";
    return 1;
  }
  if (outcome->verdict != 0)
    return ReportJobShortfall("watch", job_id, outcome->message, outcome->verdict);
  return 0;
}

}  // namespace radflux::cli
