// glTF 2.0 textures as the face texture rule reads them (face_textures.h): a material's
// baseColorTexture (times baseColorFactor) gives reflectance, its emissiveTexture (times
// emissiveFactor and KHR_materials_emissive_strength) emission, and under alphaMode MASK
// (alphaCutoff) or BLEND the base colour's alpha (times baseColorFactor's alpha) opacity;
// OPAQUE ignores alpha. Each texture reads the TEXCOORD_<texCoord> set its textureInfo
// names, mapped by the textureInfo's KHR_texture_transform when it has one (offset,
// rotation, scale; its texCoord override too). Each texture's sampler gives its wrap modes
// (wrapS, wrapT: REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT; REPEAT without a sampler); the
// filters do not matter to a mean over a footprint. Images come from the file's bytes (external file or data URI), from a bufferView,
// or, when the exact external name is missing, from the `fallback` reader (case-insensitive).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/scene/face_textures.h"
#include "tiny_gltf.h"

namespace radflux {

inline const TextureFormat kGltfTextureFormat{"baseColorTexture", "emissiveTexture",
                                               "baseColor alpha", "factors", false, false};

// Where one texture of a material reads its coordinates: TEXCOORD_<set>, mapped by
// `transform` (u' = t[0] u + t[1] v + t[2], v' = t[3] u + t[4] v + t[5]).
struct GltfTexCoordSet {
  int set = 0;
  std::array<double, 6> transform = {1, 0, 0, 0, 1, 0};
};

// The textures of material `index` of `model`: `textures` with reader keys naming the
// images ("<uri>" or "image <i>"), and the coordinate sets of the base colour (also the
// alpha's) and emissive textures. INVALID_ARGUMENT naming the material when a textureInfo
// names a texture that does not exist or a texture transform is not finite.
struct GltfMaterialTextures {
  MaterialTextures textures;
  GltfTexCoordSet base, emissive;
};
absl::StatusOr<GltfMaterialTextures> ReadGltfMaterialTextures(const tinygltf::Model& model,
                                                              int index);

// The bytes of the image a key of ReadGltfMaterialTextures names. NOT_FOUND naming why not.
TextureReader GltfImageReader(const tinygltf::Model& model, const TextureReader& fallback);

// `uv` mapped by `set.transform`.
std::vector<TexCoord> TransformTexCoords(const GltfTexCoordSet& set, std::vector<TexCoord> uv);

}  // namespace radflux
