// OBJ textures (issue 19): map_Kd gives each face its reflectance as Kd times the texture's
// mean over the face's footprint in texture space (sRGB decoded to linear, texture_image.h),
// map_Ke its emission as Ke times that mean, and a face whose map_d alpha is 0 all over its
// footprint is cut out (dropped). A face partly transparent keeps its full area (the
// transparent fraction does not let light through yet). Faces of one material whose means
// differ get their own copy of it (same name; --emit makes them all emitters).
//
// Each kind of change is one line of Scene::import_log:
//   "N faces took their reflectance from textures (map_Kd)", "... emission ... (map_Ke)",
//   "N faces fully transparent in their alpha texture (map_d) dropped", and, when a texture
//   cannot be read, "N textures not read, their materials' Kd/Ke used as they are (first at
//   wall.png: cannot open the file)" -- the scene still loads, as it would in a viewer that
//   shows a missing texture as its base colour. Faces without texture coordinates in a
//   textured material keep the material's values and are counted.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/scene/scene.h"
#include "solver/scene/texture_image.h"

namespace radflux {

// The bytes of the texture an MTL file names (the name as written there), or an error
// saying why not (NOT_FOUND for a missing file).
using TextureReader = std::function<absl::StatusOr<std::string>(const std::string& name)>;

// The texture files of one material ("" = none).
struct ObjTextureNames {
  std::string diffuse, emissive, alpha;  // map_Kd, map_Ke, map_d
  bool any() const { return !diffuse.empty() || !emissive.empty() || !alpha.empty(); }
};

// Applies the textures to `scene` in place: `names` per material, `uvs` per face (its
// vertices' texture coordinates, empty when it has none), textures read through `read`.
void ApplyObjTextures(const std::vector<ObjTextureNames>& names,
                      const std::vector<std::vector<TexCoord>>& uvs, const TextureReader& read,
                      Scene& scene);

}  // namespace radflux
