// Principals: the table of radfluxd's clients, from --token (the "default" principal, an
// admin) and --tokens-file (tokens_file.h), and the one place a call is mapped to its
// principal: by its bearer token, else by its verified TLS client certificate's CN.
#pragma once

#include <grpcpp/grpcpp.h>

#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "server/api/tokens_file.h"
#include "server/jobs/principal.h"

namespace radflux {

class Principals {
 public:
  // The table of `token` (--token; empty = none: then the "default" principal is an admin
  // with `defaults`, reached by that token) and `entries` (--tokens-file). With neither,
  // the server is open: every caller is the default admin principal. INVALID_ARGUMENT when
  // the file names a principal "default" beside --token, or repeats --token.
  static absl::StatusOr<Principals> Make(const std::string& token, std::vector<TokenEntry> entries,
                                         const PrincipalLimits& defaults);

  // The principal of a call (*out points into this table): by its "authorization: Bearer
  // T" (a token of no principal is UNAUTHENTICATED, however it connected), else by the CN
  // of the client certificate TLS verified (radfluxd --tls-client-ca) when that names a
  // principal of the tokens file, else the default principal of an open server, else
  // UNAUTHENTICATED saying what is missing.
  grpc::Status Identify(const grpc::ServerContextBase& context, const Principal** out) const;

  // The limits of the principal named `name`; the defaults for a name not in the table (a
  // job's owner since removed from the tokens file).
  PrincipalLimits LimitsOf(const std::string& name) const;
  // Whether `token` is a client's token (a worker token must not be one).
  bool IsClientToken(const std::string& token) const;
  // No tokens at all: everyone is the default admin principal.
  bool open() const { return open_; }
  size_t size() const { return principals_.size(); }

 private:
  bool open_ = false;
  PrincipalLimits defaults_;
  std::vector<Principal> principals_;
  std::map<std::string, size_t> by_token_;  // SHA-256 of the token -> principal
  std::map<std::string, size_t> by_name_;   // tokens file names (TLS CNs) -> principal
};

}  // namespace radflux
