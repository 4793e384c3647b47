#include "server/api/auth.h"

#include <openssl/crypto.h>

namespace radflux {

grpc::Status CheckBearerToken(const grpc::ServerContextBase& context, const std::string& token,
                              const std::string& flag) {
  if (token.empty()) return grpc::Status::OK;
  const auto& metadata = context.client_metadata();
  const auto it = metadata.find("authorization");
  if (it == metadata.end()) {
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                        "missing bearer token (this server needs the token of its " + flag +
                            ": pass it with " + flag + ")");
  }
  const std::string expected = "Bearer " + token;
  const grpc::string_ref& got = it->second;
  if (got.size() != expected.size() ||
      CRYPTO_memcmp(got.data(), expected.data(), got.size()) != 0) {
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED, "invalid bearer token");
  }
  return grpc::Status::OK;
}

}  // namespace radflux
