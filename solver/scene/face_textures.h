// Textures on faces (issue 19), one rule for OBJ (map_Kd, map_Ke, map_d) and glTF
// (baseColorTexture, emissiveTexture, the base colour's alpha under alphaMode MASK or BLEND):
// a face's reflectance is its material's value times the texture's mean over the face's
// footprint in texture space (sRGB decoded to linear, texture_image.h), its emission the
// same with the emissive texture. Opacity is the alpha texture's mean over the footprint
// (Material::opacity): a face less than kMinOpacity opaque is cut out (dropped); any other
// face is kept with that opacity, and the solver lets its transparent fraction through.
// Faces of one material whose means differ get their own copy of it (same name; --emit
// makes them all emitters).
//
// Each kind of change is one line of Scene::import_log ("map_Kd" etc. as the format names
// its textures, TextureFormat; "1 face took its ..." when there is one):
//   "N faces took their reflectance from textures (map_Kd)", "... emission ... (map_Ke)",
//   "N faces transparent (mean alpha < 1/255) in their alpha texture (map_d) dropped",
//   "N faces partly transparent (mean alpha in [1/255, 1)) in their alpha texture (map_d) let
//   the transparent fraction through", and, when a texture cannot be read, "N textures not
//   read; the materials using them keep their Kd/Ke (first at wall.png: cannot open the
//   file)" -- the scene still loads, as it would in a viewer that shows a missing texture as
//   its base colour. Faces without texture coordinates in a textured material keep the
//   material's values and are counted.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/scene/scene.h"
#include "solver/scene/texture_image.h"

namespace radflux {

// A face is cut out when the mean opacity over its footprint is below this (one step of
// an 8-bit alpha channel: nothing there to reflect or block).
inline constexpr double kMinOpacity = 1.0 / 255;

// The bytes of the texture named `name` (a key of MaterialTextures), or an error saying
// why not (NOT_FOUND for a missing file).
using TextureReader = std::function<absl::StatusOr<std::string>(const std::string& name)>;

// The textures of one material ("" = none), as keys for the TextureReader.
struct MaterialTextures {
  std::string diffuse, emissive, alpha;
  // A texel's opacity is its alpha (TextureFormat::alpha_from_grey: its grey value when the
  // image has no alpha channel) times alpha_scale; with alpha_cutoff >= 0 (glTF MASK) it is
  // then 1 when at least alpha_cutoff, else 0.
  double alpha_scale = 1;
  double alpha_cutoff = -1;
  // How each texture goes on outside [0, 1] (TextureMean).
  TextureWrapping diffuse_wrap{}, emissive_wrap{}, alpha_wrap{};
  bool any() const { return !diffuse.empty() || !emissive.empty() || !alpha.empty(); }
};

// What a format calls its textures (in log lines) and how it lays out texture space.
struct TextureFormat {
  std::string diffuse, emissive, alpha;  // e.g. "map_Kd", "map_Ke", "map_d"
  std::string untextured;                // the material values textures multiply: "Kd/Ke"
  bool v_up = true;             // v = 0 is the image's bottom row (OBJ), else its top (glTF)
  bool alpha_from_grey = true;  // an image without alpha channel gives its grey as alpha
};

inline const TextureFormat kObjTextureFormat{"map_Kd", "map_Ke", "map_d", "Kd/Ke", true, true};

enum class TextureSlot { kDiffuse, kEmissive, kAlpha };

// The texture coordinates of face `face` (its vertices', in order) for the texture in
// `slot`; empty when it has none.
using FaceTexCoords =
    std::function<const std::vector<TexCoord>&(size_t face, TextureSlot slot)>;

// Applies the textures to `scene` in place: `textures` per material, coordinates from `uvs`
// (indexed by the face's position in scene.faces on entry), textures read through `read`.
void ApplyFaceTextures(const std::vector<MaterialTextures>& textures, const FaceTexCoords& uvs,
                       const TextureReader& read, const TextureFormat& format, Scene& scene);

}  // namespace radflux
