// radflux-service: the service verbs of `radflux` (submit, watch, result, cancel, list),
// talking to radfluxd. `radflux` runs it for those verbs (client/service_dispatch.h); it
// can be run directly with the same arguments.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>

#include "client/service_commands.h"

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  CLI::App app{"radflux service verbs: the client of radfluxd", "radflux"};
  app.require_subcommand(1);
  int exit_code = 0;
  radflux::cli::AddServiceCommands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);   // --help
    std::fprintf(stderr, "radflux: %s\n", e.what());  // one line, as for every other error
    return 2;
  }
  return exit_code;
}
