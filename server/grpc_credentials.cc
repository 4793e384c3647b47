#include "server/grpc_credentials.h"

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

std::shared_ptr<grpc::ServerCredentials> ServerCredentialsFromFiles(const std::string& cert_file,
                                                                    const std::string& key_file) {
  if (cert_file.empty()) return grpc::InsecureServerCredentials();
  grpc::SslServerCredentialsOptions::PemKeyCertPair pair;
  if (!ReadFile(key_file, &pair.private_key) || !ReadFile(cert_file, &pair.cert_chain)) {
    return nullptr;
  }
  grpc::SslServerCredentialsOptions options;
  options.pem_key_cert_pairs.push_back(pair);
  return grpc::SslServerCredentials(options);
}

std::shared_ptr<grpc::ChannelCredentials> ChannelCredentialsFromFile(const std::string& ca_file) {
  if (ca_file.empty()) return grpc::InsecureChannelCredentials();
  grpc::SslCredentialsOptions ssl;
  if (!ReadFile(ca_file, &ssl.pem_root_certs)) return nullptr;
  return grpc::SslCredentials(ssl);
}

}  // namespace radflux
