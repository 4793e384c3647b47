#include "client/service_client.h"

#include <iostream>

#include "absl/strings/str_cat.h"
#include "wire/grpc_credentials.h"
#include "wire/proto_convert.h"

namespace radflux::cli {

Client::Client(const ConnectionFlags& c) : flags_(c) {
  std::shared_ptr<grpc::ChannelCredentials> credentials =
      ChannelCredentialsFromFile(c.tls_ca, c.tls_cert, c.tls_key);
  if (!credentials) {  // warn, and go on with TLS trusting the default roots
    std::cerr << "radflux: cannot read --tls-ca " << c.tls_ca << " / --tls-cert " << c.tls_cert
              << " / --tls-key " << c.tls_key << "\n";
    credentials = grpc::SslCredentials(grpc::SslCredentialsOptions());
  }
  // A dropped connection is retried within a second (gRPC's default backoff grows to
  // 120 s), so that a watch resumes soon after a server restart. (Not the "min" backoff:
  // gRPC uses it as the timeout of each connection attempt, 20 s by default.)
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 100);
  arguments.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 1000);
  channel_ = grpc::CreateCustomChannel(c.server, credentials, arguments);
  stub_ = v1::Radiosity::NewStub(channel_);
}

// A failed call as one line; UNAVAILABLE means nobody answered.
int Report(const grpc::Status& status, const ConnectionFlags& c) {
  if (status.error_code() == grpc::StatusCode::UNAVAILABLE) {
    std::cerr << "radflux: cannot reach radfluxd at " << c.server << " (" << status.error_message()
              << ")\n";
  } else {
    std::cerr << "radflux: server refused: "
              << absl::StatusCodeToString(static_cast<absl::StatusCode>(status.error_code()))
              << ": " << status.error_message() << "\n";
  }
  return 1;
}

// One line on stderr for a failure; server errors name the server, local ones do not.
int Fail(const absl::Status& status, const ConnectionFlags& c) {
  if (status.code() == absl::StatusCode::kUnavailable ||
      status.code() == absl::StatusCode::kUnauthenticated ||
      status.code() == absl::StatusCode::kNotFound ||
      status.code() == absl::StatusCode::kFailedPrecondition) {
    return Report(ToGrpcStatus(status), c);
  }
  std::cerr << "radflux: " << status.message() << "\n";
  return 1;
}

}  // namespace radflux::cli
