// radflux: the command-line client. `solve` and `viewfactors` run in-process; the
// service verbs (submit, watch, result, cancel, list) talk to radfluxd.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdio>

#include "client/solve_command.h"
#include "client/viewfactors_command.h"
#ifdef RADFLUX_WITH_SERVICE
#include "client/service_commands.h"
#endif

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  CLI::App app{"radflux: radiosity solver (in-process, or client of radfluxd)", "radflux"};
  app.require_subcommand(1);
  int exit_code = 0;
  radflux::cli::AddSolveCommand(app, exit_code);
  radflux::cli::AddViewFactorsCommand(app, exit_code);
#ifdef RADFLUX_WITH_SERVICE
  radflux::cli::AddServiceCommands(app, exit_code);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::fprintf(stderr, "radflux: %s\n", e.what());  // one line, as for every other error
    return 2;
  }
  return exit_code;
}
