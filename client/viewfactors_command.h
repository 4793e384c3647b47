// `radflux viewfactors SCENE --by object|group|face -o F.csv`: the view-factor matrix
// between whole named surfaces, aggregated from patch rows (area-weighted).
#pragma once

#include <CLI/CLI.hpp>

namespace radflux::cli {

void AddViewFactorsCommand(CLI::App& app, int& exit_code);

}  // namespace radflux::cli
