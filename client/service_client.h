// The client's connection to radfluxd: the connection flags, a channel with its stub and
// credentials, and how a failed call is told to the user (one line on stderr).
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <string>

#include "absl/status/status.h"
#include "radflux/v1/radiosity.grpc.pb.h"

namespace radflux::cli {

struct ConnectionFlags {
  std::string server = "localhost:50051";
  std::string token;
  std::string tls_ca;
  std::string tls_cert, tls_key;  // client certificate, for a server with --tls-client-ca
};

// A channel to `server` (TLS when --tls-ca is given) and the bearer token every call carries.
class Client {
 public:
  explicit Client(const ConnectionFlags& c);
  std::unique_ptr<grpc::ClientContext> Context() const {
    auto context = std::make_unique<grpc::ClientContext>();
    if (!flags_.token.empty()) context->AddMetadata("authorization", "Bearer " + flags_.token);
    return context;
  }
  v1::Radiosity::Stub& stub() { return *stub_; }
  const ConnectionFlags& flags() const { return flags_; }
  // Waits until the channel is connected (reconnecting as needed), at most until `deadline`.
  bool WaitForConnected(std::chrono::system_clock::time_point deadline) {
    return channel_->WaitForConnected(deadline);
  }

 private:
  ConnectionFlags flags_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Radiosity::Stub> stub_;
};

// A failed call as one line; UNAVAILABLE means nobody answered.
int Report(const grpc::Status& status, const ConnectionFlags& c);

// One line on stderr for a failure; server errors name the server, local ones do not.
int Fail(const absl::Status& status, const ConnectionFlags& c);

}  // namespace radflux::cli
