// The common ending of every radflux executable's main: parse the command line into `app`
// (whose chosen command runs in its callback) and turn the outcome into an exit code.
#pragma once

#include <CLI/CLI.hpp>

namespace radflux::cli {

// 0 after --help; 2 with one line `radflux: ...` on stderr for a command line CLI11
// refuses (naming the verb when it is not one of `app`'s); otherwise `exit_code` as the command's
// callback set it.
int RunApp(CLI::App& app, int argc, char** argv, const int& exit_code);

}  // namespace radflux::cli
