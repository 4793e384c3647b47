// radflux-service: the service verbs of `radflux` (submit, watch, result, cancel, list, view),
// talking to radfluxd, and `solve --view` (the one verb of radflux-local that serves HTTP).
// `radflux` runs it for those (client/service_dispatch.h); it can be run directly with the
// same arguments.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "client/run_app.h"
#include "client/service_commands.h"
#include "client/solve_command.h"
#include "client/view/solve_view.h"

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  CLI::App app{"radflux service verbs: the client of radfluxd", "radflux"};
  app.set_version_flag("--version", "radflux " RADFLUX_VERSION);
  app.require_subcommand(1);
  int exit_code = 0;
  radflux::cli::AddServiceCommands(app, exit_code);
  // `radflux solve --view` comes here: the solve in-process, its page served as `view`'s.
  radflux::cli::AddSolveCommand(app, exit_code, [](int port) {
    return std::make_unique<radflux::cli::SolveView>(port);
  });
  const int code = radflux::cli::RunApp(app, argc, argv, exit_code);
  // Everything the verb writes is written and closed by now; what is left is gRPC's
  // teardown of its threads and channel (~3-6 ms of a round trip, with sleeps of 1 and 2 ms
  // in its shutdown), which the kernel does as well by ending the process.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(code);
}
