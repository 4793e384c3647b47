// The tokens file of radfluxd (--tokens-file): which bearer tokens (and TLS client
// certificates) are which principal, with its rights and limits. One principal a line:
//
//   # comment (also after a line's fields); blank lines are skipped
//   PRINCIPAL TOKEN [admin] [running_jobs=N] [patches=N] [cpu_seconds=S]
//
// PRINCIPAL: 1-64 of [A-Za-z0-9_.@-]; TOKEN: the bearer token (no whitespace, not starting
// with '#'), or "-" for a principal that authenticates by TLS client certificate only (its
// certificate's CN is the PRINCIPAL name; any principal of the file may be reached that
// way). Limits left out take the server's defaults (radfluxd --principal-running-jobs, ...;
// 0 = no limit).
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "server/jobs/principal.h"

namespace radflux {

// One line of a tokens file.
struct TokenEntry {
  Principal principal;
  std::string token;  // empty: TLS client certificate only
};

// Parses the tokens file at `path`; limits a line leaves out are `defaults`. A bad line is
// INVALID_ARGUMENT "PATH:LINE: what is wrong" (a duplicate principal or token too); an
// unreadable file says so.
absl::StatusOr<std::vector<TokenEntry>> ReadTokensFile(const std::string& path,
                                                       const PrincipalLimits& defaults);

}  // namespace radflux
