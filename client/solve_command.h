// `radflux solve SCENE [options]`: the whole job in-process on all cores, no server.
#pragma once

#include <CLI/CLI.hpp>

namespace radflux::cli {

// Registers the verb; its callback sets `exit_code`.
void AddSolveCommand(CLI::App& app, int& exit_code);

}  // namespace radflux::cli
