#include "server/api/principals.h"

#include "absl/strings/str_cat.h"
#include "wire/scene_hash.h"

namespace radflux {

absl::StatusOr<Principals> Principals::Make(const std::string& token,
                                            std::vector<TokenEntry> entries,
                                            const PrincipalLimits& defaults) {
  Principals table;
  table.open_ = token.empty() && entries.empty();
  table.defaults_ = defaults;
  if (!token.empty() || table.open_) {
    table.principals_.push_back(Principal{kDefaultPrincipal, /*admin=*/true, defaults});
    if (!token.empty()) table.by_token_.emplace(Sha256Hex(token), 0);
  }
  for (TokenEntry& entry : entries) {
    const size_t index = table.principals_.size();
    if (entry.principal.name == kDefaultPrincipal && !token.empty()) {
      return absl::InvalidArgumentError(
          "the tokens file names a principal 'default': that is the principal of --token");
    }
    if (!entry.token.empty() &&
        !table.by_token_.emplace(Sha256Hex(entry.token), index).second) {
      return absl::InvalidArgumentError(absl::StrCat(
          "the tokens file gives principal '", entry.principal.name, "' the --token"));
    }
    table.by_name_.emplace(entry.principal.name, index);
    table.principals_.push_back(std::move(entry.principal));
  }
  return table;
}

PrincipalLimits Principals::LimitsOf(const std::string& name) const {
  for (const Principal& principal : principals_) {
    if (principal.name == name) return principal.limits;
  }
  return defaults_;
}

bool Principals::IsClientToken(const std::string& token) const {
  return by_token_.count(Sha256Hex(token)) > 0;
}

grpc::Status Principals::Identify(const grpc::ServerContextBase& context,
                                  const Principal** out) const {
  const auto& metadata = context.client_metadata();
  if (const auto it = metadata.find("authorization"); it != metadata.end()) {
    const std::string value(it->second.data(), it->second.size());
    constexpr std::string_view kBearer = "Bearer ";
    // Looked up by the token's hash: the lookup's timing tells nothing of the tokens.
    const auto found = value.rfind(kBearer, 0) == 0
                           ? by_token_.find(Sha256Hex(value.substr(kBearer.size())))
                           : by_token_.end();
    if (found != by_token_.end()) {
      *out = &principals_[found->second];
      return grpc::Status::OK;
    }
    if (!open()) return grpc::Status(grpc::StatusCode::UNAUTHENTICATED, "invalid bearer token");
  }
  if (const std::shared_ptr<const grpc::AuthContext> auth = context.auth_context()) {
    for (const grpc::string_ref& cn : auth->FindPropertyValues("x509_common_name")) {
      if (const auto it = by_name_.find(std::string(cn.data(), cn.size())); it != by_name_.end()) {
        *out = &principals_[it->second];
        return grpc::Status::OK;
      }
    }
  }
  if (open()) {
    *out = &principals_.front();
    return grpc::Status::OK;
  }
  return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                      "missing bearer token (this server needs the token of a principal of its "
                      "--token or --tokens-file: pass it with --token, or a TLS client "
                      "certificate whose CN names a principal of its --tokens-file)");
}

}  // namespace radflux
