// Credentials from PEM files, for radfluxd (server and worker roles) and the client, and
// the whole-file read they are built on.
#pragma once

#include <grpcpp/security/credentials.h>
#include <grpcpp/security/server_credentials.h>

#include <memory>
#include <string>

namespace radflux {

// The whole file as bytes into *out; false (and *out untouched) when it cannot be opened.
bool ReadFile(const std::string& path, std::string* out);

// TLS with the PEM certificate chain and private key files, or insecure when `cert_file` is
// empty. With `client_ca_file` (PEM), mutual TLS: every client must present a certificate
// signed by that CA, and a handshake without one fails. nullptr when a file cannot be read.
std::shared_ptr<grpc::ServerCredentials> ServerCredentialsFromFiles(
    const std::string& cert_file, const std::string& key_file,
    const std::string& client_ca_file = "");

// TLS trusting the PEM CA certificate file (the default roots when empty), presenting the
// PEM client certificate chain and key when `cert_file` is set; insecure when `ca_file` and
// `cert_file` are both empty. nullptr when a file cannot be read.
std::shared_ptr<grpc::ChannelCredentials> ChannelCredentialsFromFile(
    const std::string& ca_file, const std::string& cert_file = "",
    const std::string& key_file = "");

}  // namespace radflux
