// Following a job on radfluxd: its events as progress lines on stderr, its snapshots as
// PNGs, resumed after the last event seen when the stream drops.
#pragma once

#include <string>

#include "client/output_flags.h"
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
};

// What the flags of `radflux result` and `radflux watch` ask for.
struct OutputArgs {
  OutputFlags output;
  int threads = 0;
};

// Streams a job's events to stderr until it ends, writing each snapshot as a PNG into
// snapshots_dir (if set; then `geometry` is the job's); snapshots are asked every
// `snapshot_every` iterations (without a directory they are only counted). When the stream
// drops after its first event (a server restart), it is reopened after the last event seen,
// for up to `reconnect_seconds` of waiting each time. Returns 0 when the job SUCCEEDED,
// kExitNotConverged when it SUCCEEDED short of its tolerance (one line says so).
int WatchJob(Client& client, const std::string& job_id, const std::string& snapshots_dir,
             const JobGeometry* geometry, const OutputArgs& args, int snapshot_every,
             int reconnect_seconds);

}  // namespace radflux::cli
