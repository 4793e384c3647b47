// A stand-in `radflux` with only the service verbs, so the integration tests can run them
// before client/main.cc wires AddServiceCommands in.
#include <CLI/CLI.hpp>

#include "client/service_commands.h"

int main(int argc, char** argv) {
  CLI::App app{"radflux service verbs"};
  app.require_subcommand(1);
  int exit_code = 0;
  radflux::cli::AddServiceCommands(app, exit_code);
  CLI11_PARSE(app, argc, argv);
  return exit_code;
}
