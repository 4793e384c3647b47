#include "client/run_app.h"

#include <cstdio>

namespace radflux::cli {

int RunApp(CLI::App& app, int argc, char** argv, const int& exit_code) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);   // --help
    std::fprintf(stderr, "radflux: %s\n", e.what());  // one line, as for every other error
    return 2;
  }
  return exit_code;
}

}  // namespace radflux::cli
