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
// empty; nullptr when either file cannot be read.
std::shared_ptr<grpc::ServerCredentials> ServerCredentialsFromFiles(const std::string& cert_file,
                                                                    const std::string& key_file);

// TLS trusting the PEM CA certificate file, or insecure when `ca_file` is empty; nullptr
// when it cannot be read.
std::shared_ptr<grpc::ChannelCredentials> ChannelCredentialsFromFile(const std::string& ca_file);

}  // namespace radflux
