// Bearer-token check of an RPC: the one place the server decides who may call it.
#pragma once

#include <grpcpp/grpcpp.h>

#include <string>

namespace radflux {

// OK when `token` is empty (auth off) or the call carries "authorization: Bearer <token>";
// UNAUTHENTICATED with a message saying which is wrong otherwise (for a missing token: that
// the server needs the one of its `flag`). Constant-time compare.
grpc::Status CheckBearerToken(const grpc::ServerContextBase& context, const std::string& token,
                              const std::string& flag = "--token");

}  // namespace radflux
