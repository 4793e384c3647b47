// radflux-local: the verbs of `radflux` that run in-process (solve, viewfactors) and its
// top-level help. `radflux` runs it for every verb that is not a service verb
// (client/service_dispatch.h); it can be run directly with the same arguments.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "client/run_app.h"
#include "client/solve_command.h"
#include "client/viewfactors_command.h"

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  CLI::App app{"radflux: radiosity solver (in-process, or client of radfluxd)", "radflux"};
  app.set_version_flag("--version", "radflux " RADFLUX_VERSION);
  app.require_subcommand(1);
#ifdef RADFLUX_WITH_SERVICE
  app.footer(
      "Service verbs (client of radfluxd; `radflux VERB --help` for each):\n"
      "  submit    upload a scene and submit a job\n"
      "  watch     follow a job's progress\n"
      "  result    fetch a finished job's result: the outputs of `radflux solve`\n"
      "  cancel    cancel a queued or running job\n"
      "  list      list jobs, newest first\n"
      "  view      a job's live 3D view in the browser (also: solve SCENE --view)");
#endif
  int exit_code = 0;
  radflux::cli::AddSolveCommand(app, exit_code);
  radflux::cli::AddViewFactorsCommand(app, exit_code);
  return radflux::cli::RunApp(app, argc, argv, exit_code);
}
