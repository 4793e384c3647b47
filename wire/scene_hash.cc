#include "wire/scene_hash.h"

#include <openssl/evp.h>

#include <array>
#include <memory>
#include <string>

namespace radflux {
namespace {

// Hex of the SHA-256 of the concatenation of `parts`.
std::string HashParts(std::initializer_list<std::string_view> parts) {
  Sha256Stream hash;
  for (std::string_view part : parts) hash.Update(part);
  return hash.Hex();
}

}  // namespace

Sha256Stream::Sha256Stream() : ctx_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
  EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr);
}

void Sha256Stream::Update(std::string_view bytes) {
  EVP_DigestUpdate(ctx_.get(), bytes.data(), bytes.size());
}

std::string Sha256Stream::Hex() const {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> copy(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_MD_CTX_copy_ex(copy.get(), ctx_.get());
  return DigestHex(copy.get());
}

std::string SceneHashPrefix(uint64_t obj_size) {
  return "radflux-scene-v1\n" + std::to_string(obj_size) + "\n";
}

std::string DigestHex(EVP_MD_CTX* ctx) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx, digest.data(), &length);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    hex.push_back(kHex[digest[i] >> 4]);
    hex.push_back(kHex[digest[i] & 15]);
  }
  return hex;
}

std::string SceneContentHash(std::string_view obj, std::string_view mtl) {
  return HashParts({SceneHashPrefix(obj.size()), obj, mtl});
}

std::string MeshContentHash(std::string_view mesh) {
  return HashParts({kMeshHashPrefix, mesh});
}

std::string Sha256Hex(std::string_view data) { return HashParts({data}); }

}  // namespace radflux
