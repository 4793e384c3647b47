// The service verbs (submit, watch, result, cancel, list) live in a sibling executable,
// radflux-service, so that `radflux solve` never loads gRPC, protobuf and OpenSSL: their
// dynamic linking and start-up were 6 ms of a 50 ms Cornell solve. `radflux VERB ...`
// with a service verb replaces itself by `radflux-service VERB ...`, arguments unchanged,
// so the command line is one contract whichever binary parses it.
#pragma once

#include <string>
#include <string_view>

namespace radflux::cli {

// The verbs radflux-service implements.
bool IsServiceVerb(std::string_view verb);

// The verb of a radflux command line: the first argument that is neither an option nor the
// value of a top-level connection option (--server, --token, --tls-ca, --tls-cert,
// --tls-key may come before the verb). Empty when there is none.
std::string_view FindVerb(int argc, char** argv);

// Replaces this process by radflux-service found next to this executable, with the same
// arguments. Returns only on failure, with a message naming the path it tried.
std::string ExecServiceBinary(char** argv);

}  // namespace radflux::cli
