// The content address of an uploaded scene (OBJ + MTL or Mesh): shared by the server and the client
// so both compute the same name for the same content.
#pragma once

#include <openssl/evp.h>

#include <string>
#include <string_view>

namespace radflux {

// Lowercase hex SHA-256 of "radflux-scene-v1\n" + decimal(obj.size()) + "\n" + obj + mtl
// (the length prefix keeps the OBJ/MTL split part of the address).
std::string SceneContentHash(std::string_view obj, std::string_view mtl);

// Lowercase hex SHA-256 of "radflux-mesh-v1\n" + `mesh` (a serialized v1::Mesh as uploaded).
std::string MeshContentHash(std::string_view mesh);

// Lowercase hex of the digest `ctx` ends with (EVP_DigestFinal_ex: ctx is finished).
std::string DigestHex(EVP_MD_CTX* ctx);

// Lowercase hex SHA-256 of `data`.
std::string Sha256Hex(std::string_view data);

}  // namespace radflux
