// Following a job on radfluxd: its events as progress lines on stderr, its snapshots as
// PNGs, resumed after the last event seen when the stream drops.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "client/job_fetch.h"
#include "client/output_flags.h"
#include "client/service_client.h"

namespace radflux::cli {

// What the flags of `radflux result` and `radflux watch` ask for.
struct OutputArgs {
  OutputFlags output;
  int threads = 0;
};

// What a watch does with what it receives (each handler may be empty).
struct WatchHandlers {
  std::function<void(const v1::JobEvent&)> event;     // each event that is not a snapshot
  std::function<void(const v1::Snapshot&)> snapshot;  // each snapshot
  std::function<void(const std::string&)> note;       // a line for the user (reconnecting)
};

// What a watch saw by its end.
struct WatchOutcome {
  uint64_t last_sequence = 0;  // of the last event (not snapshot) received
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  std::string message;
  int verdict = 0;  // the final event's SucceededJobExitCode (3 short of tolerance, 4 balance off)
  int64_t snapshots = 0;
};

// Follows the job of `request` until its final event, calling `handlers` on what arrives.
// When the stream drops after its first event (a server restart), it is reopened after the
// last event seen, for up to `reconnect_seconds` of waiting each time. An error when the
// watch failed (not when the job did: see WatchOutcome::state).
absl::StatusOr<WatchOutcome> FollowJob(Client& client, const v1::WatchJobRequest& request,
                                       const WatchHandlers& handlers, int reconnect_seconds);

// Shows a job's progress on stderr (a bar on a terminal, plain lines else) until it ends, writing each snapshot as a PNG into
// snapshots_dir (if set; then `geometry` is the job's); snapshots are asked every
// `snapshot_every` iterations (without a directory they are only counted). When the stream
// drops after its first event (a server restart), it is reopened after the last event seen,
// for up to `reconnect_seconds` of waiting each time. Returns 0 when the job SUCCEEDED,
// kExitNotConverged when it SUCCEEDED short of its tolerance, kExitEnergyImbalance when its
// energy balance is off (one line says so).
int WatchJob(Client& client, const std::string& job_id, const std::string& snapshots_dir,
             const JobGeometry* geometry, const OutputArgs& args, int snapshot_every,
             int reconnect_seconds);

}  // namespace radflux::cli
