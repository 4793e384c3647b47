#include "wire/grpc_credentials.h"

#include <fstream>
#include <sstream>

namespace radflux {

bool ReadFile(const std::string& path, std::string* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::stringstream buffer;
  buffer << in.rdbuf();
  *out = buffer.str();
  return true;
}

std::shared_ptr<grpc::ServerCredentials> ServerCredentialsFromFiles(
    const std::string& cert_file, const std::string& key_file, const std::string& client_ca_file) {
  if (cert_file.empty()) return grpc::InsecureServerCredentials();
  grpc::SslServerCredentialsOptions::PemKeyCertPair pair;
  if (!ReadFile(key_file, &pair.private_key) || !ReadFile(cert_file, &pair.cert_chain)) {
    return nullptr;
  }
  grpc::SslServerCredentialsOptions options;
  options.pem_key_cert_pairs.push_back(pair);
  if (!client_ca_file.empty()) {
    if (!ReadFile(client_ca_file, &options.pem_root_certs)) return nullptr;
    options.client_certificate_request = GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY;
  }
  return grpc::SslServerCredentials(options);
}

std::shared_ptr<grpc::ChannelCredentials> ChannelCredentialsFromFile(const std::string& ca_file,
                                                                     const std::string& cert_file,
                                                                     const std::string& key_file) {
  if (ca_file.empty() && cert_file.empty()) return grpc::InsecureChannelCredentials();
  grpc::SslCredentialsOptions ssl;
  if (!ca_file.empty() && !ReadFile(ca_file, &ssl.pem_root_certs)) return nullptr;
  if (!cert_file.empty() &&
      (!ReadFile(cert_file, &ssl.pem_cert_chain) || !ReadFile(key_file, &ssl.pem_private_key))) {
    return nullptr;
  }
  return grpc::SslCredentials(ssl);
}

}  // namespace radflux
