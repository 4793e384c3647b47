// The client verbs that talk to radfluxd: submit, watch, result, cancel, list, view.
// `result` (and `watch`) take the output flags of `radflux solve`: they fetch the job's
// scene (GetScene), re-mesh it with the job's options and write what `solve` writes.
// Each accepts --server HOST:PORT (default localhost:50051), --token, --tls-ca and
// --tls-cert/--tls-key (a client certificate, for a server with --tls-client-ca), before
// or after the verb. Failures print one line ("radflux: ...") and set exit_code to 1.
#pragma once

#include <CLI/CLI.hpp>

namespace radflux::cli {

// Adds the five service verbs (and the connection flags) to `app`.
void AddServiceCommands(CLI::App& app, int& exit_code);

}  // namespace radflux::cli
