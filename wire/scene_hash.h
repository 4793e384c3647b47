// The content address of an uploaded scene (OBJ + MTL or Mesh): shared by the server and the client
// so both compute the same name for the same content.
#pragma once

#include <openssl/evp.h>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace radflux {

// A SHA-256 fed piece by piece (the same digest as of the pieces' concatenation).
class Sha256Stream {
 public:
  Sha256Stream();
  void Update(std::string_view bytes);
  // Lowercase hex of the digest of everything given so far (the stream stays usable).
  std::string Hex() const;

 private:
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx_;
};

// What SceneContentHash hashes before obj + mtl, for an OBJ of `obj_size` bytes.
std::string SceneHashPrefix(uint64_t obj_size);

// What MeshContentHash hashes before the mesh.
inline constexpr std::string_view kMeshHashPrefix = "radflux-mesh-v1\n";

// Lowercase hex SHA-256 of "radflux-scene-v1\n" + decimal(obj.size()) + "\n" + obj + mtl
// (the length prefix keeps the OBJ/MTL split part of the address): SceneHashPrefix, then
// the texts.
std::string SceneContentHash(std::string_view obj, std::string_view mtl);

// Lowercase hex SHA-256 of kMeshHashPrefix + `mesh` (a serialized v1::Mesh as uploaded).
std::string MeshContentHash(std::string_view mesh);

// Lowercase hex of the digest `ctx` ends with (EVP_DigestFinal_ex: ctx is finished).
std::string DigestHex(EVP_MD_CTX* ctx);

// Lowercase hex SHA-256 of `data`.
std::string Sha256Hex(std::string_view data);

}  // namespace radflux
