#include "client/run_app.h"

#include <cstdio>
#include <string_view>

#include "client/service_dispatch.h"

namespace radflux::cli {

int RunApp(CLI::App& app, int argc, char** argv, const int& exit_code) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // CLI11 reports a verb it does not know as a missing one.
    if (dynamic_cast<const CLI::RequiredError*>(&e) && app.get_subcommands().empty()) {
      if (const std::string_view verb = FindVerb(argc, argv); !verb.empty()) {
        std::fprintf(stderr, "radflux: unknown verb '%.*s' (`radflux --help` lists them)\n",
                     static_cast<int>(verb.size()), verb.data());
        return 2;
      }
    }
    std::fprintf(stderr, "radflux: %s\n", e.what());  // one line, as for every other error
    return 2;
  }
  return exit_code;
}

}  // namespace radflux::cli
