#include "solver/scene/obj_textures.h"

#include <map>
#include <optional>
#include <tuple>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

// Each texture decoded once; a texture that cannot be read is logged once and is null.
class TextureCache {
 public:
  TextureCache(const TextureReader& read, ImportLog& log) : read_(read), log_(log) {}

  const TextureImage* Get(const std::string& name) {
    if (name.empty()) return nullptr;
    auto [it, inserted] = images_.try_emplace(name);
    if (!inserted) return it->second ? &*it->second : nullptr;
    absl::StatusOr<std::string> bytes = read_(name);
    absl::StatusOr<TextureImage> image =
        bytes.ok() ? DecodeTexture(*bytes, name)
                   : absl::StatusOr<TextureImage>(
                         absl::NotFoundError(absl::StrCat(name, ": ", bytes.status().message())));
    if (!image.ok()) {
      log_.Add("textures_not_read", "textures not read, their materials' Kd/Ke used as they are",
               std::string(image.status().message()));
      return nullptr;
    }
    it->second = *std::move(image);
    return &*it->second;
  }

 private:
  const TextureReader& read_;
  ImportLog& log_;
  std::map<std::string, std::optional<TextureImage>> images_;
};

Rgb Times(const Rgb& a, const std::array<double, 4>& mean) {
  return {a[0] * mean[0], a[1] * mean[1], a[2] * mean[2]};
}

// The alpha of a map_d texture over a footprint: its alpha channel, or its grey value when
// it has none (map_d images are often grey).
double Alpha(const TextureImage& image, const std::vector<TexCoord>& uv) {
  const std::array<double, 4> mean = TextureMean(image, uv, /*v_up=*/true);
  return image.has_alpha ? mean[3] : mean[0];
}

}  // namespace

void ApplyObjTextures(const std::vector<ObjTextureNames>& names,
                      const std::vector<std::vector<TexCoord>>& uvs, const TextureReader& read,
                      Scene& scene) {
  TextureCache cache(read, scene.import_log);
  std::map<std::tuple<uint32_t, Rgb, Rgb>, uint32_t> variants;  // (material, rho, E) -> index
  std::vector<Face> kept;
  kept.reserve(scene.faces.size());
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    Face& face = scene.faces[f];
    const ObjTextureNames& textures = names[face.material];
    const std::string where = absl::StrCat(scene.source, ":", face.source_line);
    if (!textures.any() || uvs[f].empty()) {
      if (textures.any()) {
        scene.import_log.Add("textures_without_uv",
                             "faces in textured materials without texture coordinates kept "
                             "their Kd/Ke",
                             where);
      }
      kept.push_back(std::move(face));
      continue;
    }
    if (const TextureImage* alpha = cache.Get(textures.alpha);
        alpha && Alpha(*alpha, uvs[f]) <= 0) {
      scene.import_log.Add("transparent_faces_dropped",
                           "faces fully transparent in their alpha texture (map_d) dropped", where);
      continue;
    }
    Material material = scene.materials[face.material];
    if (const TextureImage* diffuse = cache.Get(textures.diffuse)) {
      material.reflectance = Times(material.reflectance, TextureMean(*diffuse, uvs[f], true));
      scene.import_log.Add("reflectance_from_textures",
                           "faces took their reflectance from textures (map_Kd)", where);
    }
    if (const TextureImage* emissive = cache.Get(textures.emissive)) {
      material.emission = Times(material.emission, TextureMean(*emissive, uvs[f], true));
      scene.import_log.Add("emission_from_textures",
                           "faces took their emission from textures (map_Ke)", where);
    }
    const auto key = std::make_tuple(face.material, material.reflectance, material.emission);
    auto [it, inserted] = variants.try_emplace(key, static_cast<uint32_t>(scene.materials.size()));
    if (inserted) scene.materials.push_back(std::move(material));
    face.material = it->second;
    kept.push_back(std::move(face));
  }
  scene.faces = std::move(kept);
}

}  // namespace radflux
