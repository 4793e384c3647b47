// radflux: the command-line client. `solve` and `viewfactors` run in-process; the
// service verbs (submit, watch, result, cancel, list) talk to radfluxd.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "client/solve_command.h"
#include "client/viewfactors_command.h"

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  CLI::App app{"radflux: radiosity solver (in-process, or client of radfluxd)", "radflux"};
  app.require_subcommand(1);
  int exit_code = 0;
  radflux::cli::AddSolveCommand(app, exit_code);
  radflux::cli::AddViewFactorsCommand(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return exit_code;
}
