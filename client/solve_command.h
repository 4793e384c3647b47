// `radflux solve SCENE [options]`: the whole job in-process on all cores, no server.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "nlohmann/json.hpp"
#include "solver/pipeline.h"

namespace radflux::cli {

// What `radflux solve --view` adds to a solve: its page in the browser. Provided by
// radflux-service (which serves HTTP); radflux-local has none.
class SolveObserver {
 public:
  virtual ~SolveObserver() = default;
  // Before the solve: the scene and its options; starts serving and prints the URL.
  virtual absl::Status Start(const Scene& scene, const JobOptions& options) = 0;
  // Row progress, as JobCallbacks::phase.
  virtual void Phase(int64_t done, int64_t total) = 0;
  // Each solver iteration; `p.snapshot` is set (every iteration, snapshot_every = 1).
  virtual void Iteration(const SolveProgress& p) = 0;
  // After the outputs are written: the final state, the report, the lit mesh.
  virtual void Finish(const JobResult& result, const nlohmann::json& report) = 0;
  // Serves the page until the process is stopped.
  virtual void ServeUntilStopped() = 0;
};

// Makes the observer of `radflux solve --view`, serving on 127.0.0.1:`port` (0: free).
using SolveObserverFactory = std::function<std::unique_ptr<SolveObserver>(int port)>;

// Registers the verb; its callback sets `exit_code`. Without `view`, --view is refused
// (radflux-local: `radflux` hands `solve --view` to radflux-service).
void AddSolveCommand(CLI::App& app, int& exit_code, SolveObserverFactory view = nullptr);

}  // namespace radflux::cli
