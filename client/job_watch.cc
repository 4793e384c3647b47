#include "client/job_watch.h"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "absl/strings/str_cat.h"
#include "client/exit_status.h"
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
  return WriteOutputs(flags, geometry.scene, geometry.mesh, radiosity, args.threads);
}

// One progress line of a job event on stderr.
void PrintEvent(const v1::JobEvent& event) {
  const v1::Progress& p = event.progress();
  std::cerr << "[" << event.sequence() << "] " << v1::JobState_Name(event.state()) << " "
            << v1::Phase_Name(event.phase());
  if (event.phase() == v1::PHASE_ROWS && p.rows_total() > 0) {
    std::cerr << " rows " << p.rows_done() << "/" << p.rows_total() << " ("
              << static_cast<int64_t>(p.rays_per_second()) << " rays/s, ETA "
              << static_cast<int>(p.eta_seconds()) << " s)";
  }
  if (event.phase() == v1::PHASE_SOLVE && p.iteration() > 0) {
    std::cerr << " iteration " << p.iteration() << " residual " << p.residual();
  }
  if (!event.message().empty()) std::cerr << ": " << event.message();
  std::cerr << "\n";
}

// True when a watch stream that failed with `code` before its job's final event may be
// reopened: the server went away (restart, network) rather than refused the watch.
bool StreamMayResume(grpc::StatusCode code) {
  return code == grpc::StatusCode::UNAVAILABLE || code == grpc::StatusCode::CANCELLED ||
         code == grpc::StatusCode::UNKNOWN || code == grpc::StatusCode::INTERNAL ||
         code == grpc::StatusCode::DEADLINE_EXCEEDED;
}

// What a watch of `job_id` has seen so far, across reconnections.
struct WatchProgress {
  uint64_t last_sequence = 0;  // of the last event (not snapshot) received
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  std::string message;
  bool converged = true;  // false when the final event says the solve stopped short
  int64_t snapshots = 0;
};

// One WatchJob stream from after progress->last_sequence until the job's final event (the
// stream is then cancelled: the result can be asked for at once, without waiting for the
// stream's end) or until the stream ends; returns its status.
grpc::Status WatchStream(Client& client, v1::WatchJobRequest request,
                         const std::string& snapshots_dir, const JobGeometry* geometry,
                         const OutputArgs& args, WatchProgress* progress) {
  request.set_after_sequence(progress->last_sequence);
  auto context = client.Context();
  auto reader = client.stub().WatchJob(context.get(), request);
  v1::JobEvent event;
  while (reader->Read(&event)) {
    if (event.has_snapshot()) {
      ++progress->snapshots;
      if (snapshots_dir.empty()) continue;
      if (absl::Status s = WriteSnapshotPng(event.snapshot(), *geometry, snapshots_dir, args);
          !s.ok()) {
        std::cerr << "radflux: snapshot " << event.snapshot().iteration() << ": " << s.message()
                  << "\n";
      }
      continue;
    }
    progress->last_sequence = event.sequence();
    progress->state = event.state();
    progress->message = event.message();
    progress->converged = !event.has_converged() || event.converged();
    PrintEvent(event);
    if (IsTerminal(event.state())) {
      context->TryCancel();
      break;
    }
  }
  return reader->Finish();
}

}  // namespace

// Streams a job's events to stderr until it ends, writing each snapshot as a PNG into
// snapshots_dir (if set; then `geometry` is the job's); snapshots are asked every
// `snapshot_every` iterations (without a directory they are only counted). When the stream
// drops after its first event (a server restart), it is reopened after the last event seen,
// for up to `reconnect_seconds` of waiting each time. Returns 0 when the job SUCCEEDED,
// kExitNotConverged when it SUCCEEDED short of its tolerance (one line says so).
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
  WatchProgress progress;
  for (;;) {
    const grpc::Status status =
        WatchStream(client, request, snapshots_dir, geometry, args, &progress);
    if (IsTerminal(progress.state)) break;
    if (progress.last_sequence == 0 || reconnect_seconds <= 0 ||
        !StreamMayResume(status.error_code())) {
      if (!status.ok()) return Report(status, client.flags());
      break;
    }
    std::cerr << "radflux: watch of " << job_id << " dropped after event " << progress.last_sequence
              << " (" << status.error_message() << "); reconnecting\n";
    if (!client.WaitForConnected(std::chrono::system_clock::now() +
                                 std::chrono::seconds(reconnect_seconds))) {
      return Report(grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                 absl::StrCat("no answer for ", reconnect_seconds, " s")),
                    client.flags());
    }
  }
  if (request.snapshot_every() > 0) std::cerr << progress.snapshots << " snapshots received\n";
  if (progress.state != v1::JOB_STATE_SUCCEEDED) {
    std::cerr << "radflux: job " << job_id << " ended " << v1::JobState_Name(progress.state)
              << (progress.message.empty() ? "" : ": " + progress.message) << "\n";
    return 1;
  }
  if (!progress.converged) return ReportJobNotConverged("watch", job_id, progress.message);
  return 0;
}

}  // namespace radflux::cli
