// `radflux` is a dispatcher, as git is for git-VERB: it reads the verb and replaces itself by
// the sibling executable that implements it, arguments unchanged, so the command line is one
// contract whichever binary parses it:
//   radflux-service  the service verbs (submit, watch, result, cancel, list, view) and
//                    `solve --view`: gRPC, OpenSSL, HTTP;
//   radflux-local    everything else (solve, viewfactors, --help): the in-process solver.
// The dispatcher links only the C library, statically: the hop costs about 1 ms, where
// starting either side's libraries costs 8-18 ms (bench/RESULTS.md, "Service overhead").
#pragma once

#include <string_view>

namespace radflux::cli {

// The verbs radflux-service implements.
bool IsServiceVerb(std::string_view verb);

// The verb of a radflux command line: the first argument that is neither an option nor the
// value of a top-level connection option (--server, --token, --tls-ca, --tls-cert,
// --tls-key may come before the verb). Empty when there is none.
std::string_view FindVerb(int argc, char** argv);

// True for `solve ... --view`: a local solve whose page is served over HTTP, which
// radflux-service does (radflux-local loads no HTTP or TLS library).
bool IsSolveWithView(int argc, char** argv);

// The sibling executable for a command line: "radflux-service" (service verbs and
// `solve --view`) or "radflux-local".
const char* SiblingFor(int argc, char** argv);

// Replaces this process by the executable `name` found next to this one, with the same
// arguments. Returns only on failure, having printed to stderr a message naming the path
// it tried and why.
void ExecSibling(const char* name, char** argv);

}  // namespace radflux::cli
