#include "wire/scene_hash.h"

#include <openssl/evp.h>

#include <array>
#include <memory>
#include <string>

namespace radflux {
namespace {

// Hex of the SHA-256 of the concatenation of `parts`.
std::string HashParts(std::initializer_list<std::string_view> parts) {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
  for (std::string_view part : parts) EVP_DigestUpdate(ctx.get(), part.data(), part.size());
  return DigestHex(ctx.get());
}

}  // namespace

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
  const std::string prefix = "radflux-scene-v1\n" + std::to_string(obj.size()) + "\n";
  return HashParts({prefix, obj, mtl});
}

std::string MeshContentHash(std::string_view mesh) {
  return HashParts({"radflux-mesh-v1\n", mesh});
}

std::string Sha256Hex(std::string_view data) { return HashParts({data}); }

}  // namespace radflux
